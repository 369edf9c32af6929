#include "rayint/scene/pipeline.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>
#include <stdexcept>

#include "rayint/core/cpu_clock.hpp"
#include "rayint/core/parallel.hpp"
#include "rayint/scene/grid_field.hpp"

namespace rayint {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

const char* role_name(EffectInfo::Role r) {
  switch (r) {
    case EffectInfo::Role::term: return "term";
    case EffectInfo::Role::attenuation_term: return "attenuation_term";
    case EffectInfo::Role::modifier: return "modifier";
  }
  return "term";
}

struct ErrorAccumulator {
  double max_abs = 0.0, sum_abs = 0.0, peak = 0.0, ref_err = 0.0, seconds = 0.0;
  long long rays = 0, channels = 0;
  bool converged = true;
  void add(const Rgb& approx, const Rgb& ref, const Rgb& ref_error) {
    ++rays;
    for (int c = 0; c < kChannels; ++c) {
      const double e = std::abs(approx[c] - ref[c]);
      max_abs = std::max(max_abs, e);
      sum_abs += e;
      ++channels;
      peak = std::max(peak, std::abs(ref[c]));
      ref_err = std::max(ref_err, ref_error[c]);
    }
  }
  void merge(const ErrorAccumulator& o) {
    max_abs = std::max(max_abs, o.max_abs);
    sum_abs += o.sum_abs;
    peak = std::max(peak, o.peak);
    ref_err = std::max(ref_err, o.ref_err);
    seconds += o.seconds;
    rays += o.rays;
    channels += o.channels;
    converged = converged && o.converged;
  }
  TermError result() const {
    TermError t;
    t.rays = rays;
    t.max_abs = max_abs;
    t.mean_abs = channels > 0 ? sum_abs / static_cast<double>(channels) : 0.0;
    t.peak_reference = peak;
    t.max_rel_to_peak = peak > 0.0 ? max_abs / peak : (max_abs > 0.0 ? INFINITY : 0.0);
    t.max_reference_error = ref_err;
    t.reference_converged = converged;
    t.reference_seconds = seconds;
    return t;
  }
};

}  // namespace

MethodSpec effective_method(const Scene& scene, const EffectInfo& effect) {
  const auto it = scene.methods.find(effect.name);
  if (it != scene.methods.end()) return it->second;
  if (effect.name == "absorption" || effect.name == "emission")
    return parse_effect_method(effect, exact_along_rays(scene.medium.field()) ? "exact" : "riemann:n=128");
  if (effect.name == "shadows") {
    MethodSpec s = parse_effect_method(effect, "shadow_rays");
    const auto ss = scene.methods.find("single_scattering");
    s.params["n"] = ss != scene.methods.end() ? ss->second.text("n", "128") : "128";
    return s;
  }
  if (effect.default_method.empty()) return MethodSpec{};
  return parse_effect_method(effect, effect.default_method);
}

ScenePipeline::ScenePipeline(const Scene& scene, unsigned threads)
    : scene_(scene), threads_(resolve_threads(threads)) {
  if (scene.camera) camera_rays_.emplace(*scene.camera);
  for (const std::string& name : scene.effects)
    if (find_effect(name) == nullptr) throw std::invalid_argument("unknown effect " + name);
  const Clock::time_point t0 = Clock::now();
  const double c0 = process_cpu_seconds();
  shadowing_ = make_shadowing(scene, threads_);
  const bool absorption = scene.has("absorption");
  const bool shadows = scene.has("shadows");
  // A blanked image (hidden cubes, grid/voxel_grid.hpp) is empty there. Only the exact absorption
  // and emission integrals leave those cubes out; every sampling method reads the density by
  // value, and a value cannot say "empty": refused rather than integrating the hidden voxels.
  if (const auto* g = dynamic_cast<const GridField*>(&scene.medium.field()); g != nullptr && g->grid().has_hidden_cubes())
    for (const EffectInfo& info : effect_registry())
      if (scene.has(info.name) &&
          ((info.name != "absorption" && info.name != "emission") || effective_method(scene, info).name != "exact"))
        throw std::invalid_argument("the grid is a blanked image (" + std::to_string(g->grid().hidden_cube_count()) +
                                    " hidden voxels, vtkGhostType): effect " + info.name +
                                    " needs method exact of absorption/emission (sampling would read the hidden voxels)");
  for (const EffectInfo& info : effect_registry()) {
    if (!scene.has(info.name) || info.role == EffectInfo::Role::modifier) continue;
    if (!info.make)
      throw std::invalid_argument("effect " + info.name + " is not available in this build (" +
                                  info.summary + ")");
    const auto settings = scene.settings.find(info.name);
    const EffectContext ctx{scene, effective_method(scene, info),
                            settings != scene.settings.end() ? &settings->second : nullptr,
                            shadowing_.get(), absorption, shadows};
    // Each effect's own set-up (e.g. the discrete-ordinates solve) is timed and reported with it.
    const Clock::time_point te = Clock::now();
    const double ce = process_cpu_seconds();
    effects_.push_back(info.make(ctx));
    effect_setup_.push_back({seconds_since(te), process_cpu_seconds() - ce});
    infos_.push_back(&info);
  }
  setup_seconds_ = seconds_since(t0);
  setup_cpu_seconds_ = process_cpu_seconds() - c0;
}

long long ScenePipeline::ray_count() const {
  if (scene_.camera) return static_cast<long long>(scene_.camera->width) * scene_.camera->height;
  return static_cast<long long>(scene_.rays.size());
}

PixelRay ScenePipeline::ray(long long index) const {
  PixelRay pr;
  if (scene_.camera) {
    const Camera& cam = *scene_.camera;
    const int x = static_cast<int>(index % cam.width);
    const int y = static_cast<int>(index / cam.width);
    pr.ray = camera_rays_->ray_for_pixel(x, y);  // cam.ray_for_pixel's bits
    pr.background = scene_.background.at((x + 0.5) / cam.width, (y + 0.5) / cam.height);
  } else {
    pr.ray = scene_.rays[static_cast<std::size_t>(index)];
    pr.background = scene_.background.color;
  }
  return pr;
}

SceneRenderPart ScenePipeline::render_part(const SceneRenderOptions& options, const ShardSpec& shard) const {
  SceneRenderPart out;
  const unsigned threads = options.threads != 0 ? options.threads : threads_;
  out.threads = threads;
  const long long count = ray_count();
  out.width = scene_.camera ? scene_.camera->width : static_cast<int>(count);
  out.height = scene_.camera ? scene_.camera->height : 1;
  // A line is an image row (camera) or one explicit ray: the unit a shard owns.
  const long long per_line = scene_.camera ? out.width : 1;
  out.lines = scene_.camera ? out.height : count;
  const IndexRange band = shard_range(static_cast<std::size_t>(out.lines), shard);
  out.line_begin = static_cast<long long>(band.begin);
  out.line_end = static_cast<long long>(band.end);
  const long long first = out.line_begin * per_line;
  const long long n = (out.line_end - out.line_begin) * per_line;
  out.pixels.assign(static_cast<std::size_t>(n), Rgb{});
  const std::size_t ne = effects_.size();
  const bool absorption = scene_.has("absorption");
  const bool keep_terms = !scene_.camera;
  if (keep_terms) out.ray_terms.assign(static_cast<std::size_t>(n), std::vector<Rgb>(ne));

  // work[worker][e] for the term effects, work[worker][ne] for shadows.
  std::vector<std::vector<EffectWork>> work(threads, std::vector<EffectWork>(ne + 1));
  // line_sums[line][e]: each term summed over a line, and [ne] the whole pixel (for means).
  // Summed per line and then over the lines in order, so the means do not depend on the thread
  // count, on which worker took which line, or on how the lines were split into shards.
  std::mutex progress_mutex;
  long long lines_done = 0;
  const long long lines = out.line_end - out.line_begin;
  out.line_sums.assign(static_cast<std::size_t>(lines), std::vector<Rgb>(ne + 1, Rgb{}));
  const Clock::time_point t_render = Clock::now();
  const double cpu_render = process_cpu_seconds();
  parallel_for(lines, threads, [&](long long line, unsigned w) {
    std::vector<Rgb>& sums = out.line_sums[static_cast<std::size_t>(line)];
    for (long long x = 0; x < per_line; ++x) {
      const long long local = line * per_line + x;
      const PixelRay pr = ray(first + local);
      Rgb pixel = absorption ? Rgb{} : pr.background;
      for (std::size_t e = 0; e < ne; ++e) {
        const Clock::time_point t0 = Clock::now();
        const double c0 = thread_cpu_seconds();
        const Rgb term = effects_[e]->term(pr, work[w][e], work[w][ne]);
        work[w][e].cpu_seconds += thread_cpu_seconds() - c0;
        work[w][e].seconds += seconds_since(t0);
        for (int c = 0; c < kChannels; ++c) {
          pixel[c] += term[c];
          sums[e][c] += term[c];
        }
        if (keep_terms) out.ray_terms[static_cast<std::size_t>(local)][e] = term;
      }
      out.pixels[static_cast<std::size_t>(local)] = pixel;
      for (int c = 0; c < kChannels; ++c) sums[ne][c] += pixel[c];
    }
    if (options.progress) {
      std::lock_guard<std::mutex> lock(progress_mutex);
      options.progress(static_cast<double>(++lines_done) / static_cast<double>(std::max(lines, 1LL)));
    }
  });
  out.render_seconds = seconds_since(t_render);
  out.render_cpu_seconds = process_cpu_seconds() - cpu_render;
  out.setup_seconds = setup_seconds_;
  out.setup_cpu_seconds = setup_cpu_seconds_;
  out.work.assign(ne + 1, EffectWork{});
  for (std::size_t e = 0; e <= ne; ++e) {
    for (unsigned w = 0; w < threads; ++w) out.work[e].add(work[w][e]);
    if (e < ne) {
      out.work[e].setup_seconds = effect_setup_[e].first;
      out.work[e].setup_cpu_seconds = effect_setup_[e].second;
    } else if (scene_.has("shadows")) {
      out.work[e].setup_seconds = shadowing_->setup_seconds();
      out.work[e].setup_cpu_seconds = shadowing_->setup_cpu_seconds();
    }
  }
  return out;
}

SceneRenderResult ScenePipeline::assemble(const std::vector<SceneRenderPart>& parts) const {
  SceneRenderResult out;
  const long long count = ray_count();
  const int width = scene_.camera ? scene_.camera->width : static_cast<int>(count);
  const int height = scene_.camera ? scene_.camera->height : 1;
  const long long per_line = scene_.camera ? width : 1;
  const long long lines = scene_.camera ? height : count;
  const std::size_t ne = effects_.size();
  out.image = Image(width, height);
  if (!scene_.camera) out.ray_terms.assign(static_cast<std::size_t>(count), std::vector<Rgb>(ne));
  std::vector<EffectWork> work(ne + 1);
  std::vector<const std::vector<Rgb>*> line_sums(static_cast<std::size_t>(lines), nullptr);
  long long rendered = 0;
  for (const SceneRenderPart& p : parts) {
    if (p.width != width || p.height != height || p.lines != lines || p.line_begin < 0 ||
        p.line_begin > p.line_end || p.line_end > lines || p.work.size() != ne + 1 ||
        p.line_sums.size() != static_cast<std::size_t>(p.line_end - p.line_begin) ||
        p.pixels.size() != static_cast<std::size_t>((p.line_end - p.line_begin) * per_line) ||
        (!scene_.camera && p.ray_terms.size() != p.pixels.size()))
      throw std::invalid_argument("a part of a " + std::to_string(width) + " x " + std::to_string(height) +
                                  " render of " + std::to_string(ne) + " terms does not fit it");
    for (long long l = p.line_begin; l < p.line_end; ++l) {
      const std::vector<Rgb>& sums = p.line_sums[static_cast<std::size_t>(l - p.line_begin)];
      if (sums.size() != ne + 1 || line_sums[static_cast<std::size_t>(l)] != nullptr)
        throw std::invalid_argument("line " + std::to_string(l) + " of the render is in two parts");
      line_sums[static_cast<std::size_t>(l)] = &sums;
    }
    const long long first = p.line_begin * per_line;
    for (std::size_t i = 0; i < p.pixels.size(); ++i) {
      const long long index = first + static_cast<long long>(i);
      out.image.at(static_cast<int>(index % width), static_cast<int>(index / width)) = p.pixels[i];
      if (!scene_.camera) out.ray_terms[static_cast<std::size_t>(index)] = p.ray_terms[i];
    }
    rendered += static_cast<long long>(p.pixels.size());
    for (std::size_t e = 0; e <= ne; ++e) work[e].add(p.work[e]);
    out.render_seconds += p.render_seconds;
    out.render_cpu_seconds += p.render_cpu_seconds;
    out.setup_seconds += p.setup_seconds;
    out.setup_cpu_seconds += p.setup_cpu_seconds;
    out.threads = std::max(out.threads, p.threads);
  }

  for (std::size_t e = 0; e < ne; ++e) {
    EffectReport r;
    r.effect = effects_[e]->name();
    r.method = effects_[e]->method_label();
    r.role = role_name(infos_[e]->role);
    r.work = work[e];
    for (const std::vector<Rgb>* sums : line_sums)
      if (sums)
        for (int c = 0; c < kChannels; ++c) r.mean_term[c] += (*sums)[e][c];
    for (int c = 0; c < kChannels; ++c) r.mean_term[c] /= static_cast<double>(std::max(rendered, 1LL));
    out.effects.push_back(r);
  }
  for (const std::vector<Rgb>* sums : line_sums)
    if (sums)
      for (int c = 0; c < kChannels; ++c) out.image_mean[c] += (*sums)[ne][c];
  for (int c = 0; c < kChannels; ++c) out.image_mean[c] /= static_cast<double>(std::max(rendered, 1LL));
  if (scene_.has("shadows")) {
    EffectReport r;
    r.effect = "shadows";
    r.method = shadowing_->label();
    r.role = "modifier";
    r.work = work[ne];
    out.effects.push_back(r);
  }
  return out;
}

SceneRenderResult ScenePipeline::render(const SceneRenderOptions& options) const {
  SceneRenderResult out = assemble({render_part(options, ShardSpec{})});
  const unsigned threads = out.threads;
  const long long count = ray_count();
  const int width = scene_.camera ? scene_.camera->width : static_cast<int>(count);
  const int height = scene_.camera ? scene_.camera->height : 1;
  const std::size_t ne = effects_.size();
  const bool absorption = scene_.has("absorption");

  if (options.error_grid > 0 && count > 0) {
    std::vector<long long> subset;
    if (scene_.camera) {
      const int k = options.error_grid;
      for (int j = 0; j < k; ++j)
        for (int i = 0; i < k; ++i) {
          const int x = std::min(width - 1, static_cast<int>((i + 0.5) * width / k));
          const int y = std::min(height - 1, static_cast<int>((j + 0.5) * height / k));
          subset.push_back(static_cast<long long>(y) * width + x);
        }
    } else {
      for (long long i = 0; i < count; ++i) subset.push_back(i);
    }
    // One accumulator per sampled ray, merged in order: independent of the thread count.
    std::vector<std::vector<ErrorAccumulator>> acc(subset.size(), std::vector<ErrorAccumulator>(ne + 1));
    const Clock::time_point t_err = Clock::now();
    std::mutex error_progress_mutex;
    std::size_t error_rays_done = 0;
    parallel_for(static_cast<long long>(subset.size()), threads, [&](long long s) {
      const PixelRay pr = ray(subset[static_cast<std::size_t>(s)]);
      std::vector<ErrorAccumulator>& ray_acc = acc[static_cast<std::size_t>(s)];
      EffectWork scratch, shadow_scratch;
      Rgb total_approx = absorption ? Rgb{} : pr.background;
      Rgb total_ref = total_approx, total_ref_err{};
      for (std::size_t e = 0; e < ne; ++e) {
        const Rgb approx = effects_[e]->term(pr, scratch, shadow_scratch);
        const Clock::time_point t0 = Clock::now();
        const ReferenceValue ref = effects_[e]->reference(pr);
        ray_acc[e].seconds += seconds_since(t0);
        ray_acc[e].converged = ray_acc[e].converged && ref.converged;
        ray_acc[e].add(approx, ref.value, ref.error_estimate);
        for (int c = 0; c < kChannels; ++c) {
          total_approx[c] += approx[c];
          total_ref[c] += ref.value[c];
          total_ref_err[c] += ref.error_estimate[c];
        }
      }
      ray_acc[ne].add(total_approx, total_ref, total_ref_err);
      if (options.error_progress) {
        std::lock_guard<std::mutex> lock(error_progress_mutex);
        options.error_progress(static_cast<double>(++error_rays_done) / static_cast<double>(subset.size()));
      }
    });
    out.error_seconds = seconds_since(t_err);
    for (std::size_t e = 0; e <= ne; ++e) {
      ErrorAccumulator a;
      for (const std::vector<ErrorAccumulator>& ray_acc : acc) a.merge(ray_acc[e]);
      if (e < ne) {
        out.effects[e].has_error = true;
        out.effects[e].error = a.result();
      } else {
        out.has_total_error = true;
        out.total_error = a.result();
      }
    }
  }
  return out;
}

ReferenceImage ScenePipeline::reference_image(unsigned threads,
                                              const std::function<void(double)>& progress) const {
  ReferenceImage out;
  const Clock::time_point t0 = Clock::now();
  const long long count = ray_count();
  const int width = scene_.camera ? scene_.camera->width : static_cast<int>(count);
  const int height = scene_.camera ? scene_.camera->height : 1;
  out.value = Image(width, height);
  out.error = Image(width, height);
  const bool absorption = scene_.has("absorption");
  std::vector<long long> evaluations(static_cast<std::size_t>(height), 0);
  std::vector<long long> unconverged(static_cast<std::size_t>(height), 0);
  std::mutex progress_mutex;
  long long rows_done = 0;
  parallel_for(height, threads != 0 ? threads : threads_, [&](long long row) {
    for (int x = 0; x < width; ++x) {
      const PixelRay pr = ray(row * width + x);
      Rgb value = absorption ? Rgb{} : pr.background;
      Rgb error{};
      bool converged = true;
      for (const std::unique_ptr<Effect>& effect : effects_) {
        const ReferenceValue ref = effect->reference(pr);
        for (int c = 0; c < kChannels; ++c) {
          value[c] += ref.value[c];
          error[c] += ref.error_estimate[c];
        }
        evaluations[static_cast<std::size_t>(row)] += ref.evaluations;
        converged = converged && ref.converged;
      }
      out.value.at(x, static_cast<int>(row)) = value;
      out.error.at(x, static_cast<int>(row)) = error;
      if (!converged) ++unconverged[static_cast<std::size_t>(row)];
    }
    if (progress) {
      std::lock_guard<std::mutex> lock(progress_mutex);
      progress(static_cast<double>(++rows_done) / static_cast<double>(height));
    }
  });
  for (long long e : evaluations) out.evaluations += e;
  for (long long u : unconverged) out.unconverged += u;
  for (const Rgb& e : out.error.pixels)
    for (int c = 0; c < kChannels; ++c) out.max_error = std::max(out.max_error, e[c]);
  out.seconds = seconds_since(t0);
  return out;
}

bool Scene::has(const std::string& effect) const {
  for (const std::string& e : effects)
    if (e == effect) return true;
  return false;
}

}  // namespace rayint
