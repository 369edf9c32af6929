// The higher-order cell and voxel-grid study (cells_study.hpp): samples, the three
// evaluations per ray (decomposed + exact at each level, polynomial ODE, 50-digit polynomial
// reference), and the tables.
#include "rayint/studies/cells_study.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <ctime>
#include <mutex>
#include <random>
#include <stdexcept>

#include "rayint/core/parallel.hpp"
#include "rayint/metrics/error_metrics.hpp"
#include "rayint/cells/poly_ode.hpp"
#include "rayint/grid/voxel_grid.hpp"
#include "rayint/integrators/exact.hpp"
#include "rayint/reference/poly_reference.hpp"

namespace rayint {

namespace {

// Times are CPU time of the calling thread (CLOCK_THREAD_CPUTIME_ID), so that they mean the
// same on a loaded machine and with several worker threads; the total is wall-clock.
struct ThreadClock {
  using time_point = double;
  static double now() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
  }
};
using Clock = ThreadClock;
double seconds_since(double t0) { return Clock::now() - t0; }
double wall_seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::mt19937_64 sample_rng(std::uint64_t seed, std::uint64_t kind, std::uint64_t index) {
  std::seed_seq seq{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                    static_cast<std::uint32_t>(kind), static_cast<std::uint32_t>(index),
                    static_cast<std::uint32_t>(index >> 32)};
  return std::mt19937_64(seq);
}

double ray_error(const RayResult& r, const ReferenceRay& ref) {
  double e = 0.0;
  for (int c = 0; c < kChannels; ++c) e = std::max(e, relative_error(r.intensity[c], ref.intensity[c]));
  return e;
}

const Rgb kBackground{0.2, 0.5, 0.8};

// Least-squares slope of log(y) on log(x), negated (the order p of y ~ x^-p).
double fitted_order(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!(y[i] > 0) || !std::isfinite(y[i])) continue;
    const double lx = std::log(x[i]), ly = std::log(y[i]);
    sx += lx; sy += ly; sxx += lx * lx; sxy += lx * ly;
    ++n;
  }
  if (n < 2) return std::nan("");
  return -(n * sxy - sx * sy) / (n * sxx - sx * sx);
}

using CellSample = CellRaySample;

CellSample evaluate_cell_ray(const HigherOrderCell& cell, const TransferFunctions& tf,
                             const ViewRay& ray, const CellsStudyOptions& o) {
  CellSample s;
  auto t0 = Clock::now();
  const PolyRay poly = cell_poly_ray(cell, ray, kBackground);
  const ReferenceRay ref = reference_poly_ray(tf, poly);
  s.reference_s = seconds_since(t0);
  s.pieces = ref.pieces;
  for (int c = 0; c < kChannels; ++c)
    s.bound_rel = std::max(s.bound_rel, ref.error_bound[c] / std::abs(ref.intensity[c].hi));
  const ExactIntegrator exact(tf);
  for (int level : o.levels) {
    t0 = Clock::now();
    const Ray linear = decomposed_ray(cell, ray, level, kBackground);
    s.level_decompose_s.push_back(seconds_since(t0));
    t0 = Clock::now();
    const RayResult r = exact.integrate(linear, nullptr);
    s.level_exact_s.push_back(seconds_since(t0));
    s.level_error.push_back(ray_error(r, ref));
    s.level_segments.push_back(static_cast<double>(linear.segments.size()));
  }
  OdeOptions ode_opt;
  ode_opt.rtol = o.ode_rtol;
  const PolyOdeIntegrator ode(tf, ode_opt);
  Diagnostics diag;
  t0 = Clock::now();
  const RayResult r = ode.integrate(poly, &diag);
  s.ode_s = seconds_since(t0);
  s.ode_error = ray_error(r, ref);
  s.ode_steps = diag.stats["steps"];
  return s;
}

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

// The rays of the cells [cells.begin, cells.end) of one type, in order.
std::vector<CellSample> sample_cell_type(CellType type, const CellsStudyOptions& o, IndexRange cells,
                                         std::mutex& progress_mutex) {
  const auto n_cells = static_cast<long long>(cells.size());
  std::vector<CellSample> samples(cells.size() * static_cast<std::size_t>(o.rays_per_cell));
  std::atomic<long long> done{0};
  const auto kind = static_cast<std::uint64_t>(type);
  parallel_for(n_cells, o.threads, [&](long long item) {
    const auto i = static_cast<std::uint64_t>(cells.begin) + static_cast<std::uint64_t>(item);
    std::mt19937_64 rng = sample_rng(o.seed, kind, i);
    const HigherOrderCell cell = random_cell(type, rng());
    const TransferFunctions tf = random_transfer_functions(rng());
    for (int r = 0; r < o.rays_per_cell; ++r) {
      const ViewRay ray = random_ray_through(cell, rng());
      samples[static_cast<std::size_t>(item) * static_cast<std::size_t>(o.rays_per_cell) +
              static_cast<std::size_t>(r)] = evaluate_cell_ray(cell, tf, ray, o);
    }
    const long long k = ++done;
    if (o.progress && (k % std::max(1LL, n_cells / 10) == 0 || k == n_cells)) {
      std::lock_guard<std::mutex> lock(progress_mutex);
      o.progress(std::string(cell_type_name(type)) + ": " + std::to_string(k) + "/" +
                 std::to_string(n_cells) + " cells");
    }
  });
  return samples;
}

CellTypeResult summarise_cell_type(CellType type, const CellsStudyOptions& o,
                                   const std::vector<CellSample>& samples) {
  CellTypeResult out;
  out.type = cell_type_name(type);
  out.samples = static_cast<int>(samples.size());
  std::vector<double> levels, medians, maxima;
  for (std::size_t l = 0; l < o.levels.size(); ++l) {
    std::vector<double> err, seg, dec, ex;
    for (const auto& s : samples) {
      err.push_back(s.level_error[l]);
      seg.push_back(s.level_segments[l]);
      dec.push_back(s.level_decompose_s[l]);
      ex.push_back(s.level_exact_s[l]);
    }
    LevelResult lr;
    lr.level = o.levels[l];
    lr.rel = error_stats(err);
    lr.segments_per_ray = mean(seg);
    lr.decompose_us_per_ray = 1e6 * mean(dec);
    lr.exact_us_per_ray = 1e6 * mean(ex);
    out.levels.push_back(lr);
    levels.push_back(lr.level);
    medians.push_back(lr.rel.median);
    maxima.push_back(lr.rel.max);
  }
  out.order_median = fitted_order(levels, medians);
  out.order_max = fitted_order(levels, maxima);
  for (std::size_t l = 0; l + 1 < levels.size(); ++l)
    out.order_steps.push_back(std::log(medians[l] / medians[l + 1]) / std::log(levels[l + 1] / levels[l]));
  std::vector<double> ode_err, ode_t, ode_steps, ref_t, pieces;
  for (const auto& s : samples) {
    ode_err.push_back(s.ode_error);
    ode_t.push_back(s.ode_s);
    ode_steps.push_back(s.ode_steps);
    ref_t.push_back(s.reference_s);
    pieces.push_back(s.pieces);
    out.max_reference_bound_rel = std::max(out.max_reference_bound_rel, s.bound_rel);
  }
  out.ode_rel = error_stats(ode_err);
  out.ode_us_per_ray = 1e6 * mean(ode_t);
  out.ode_steps_per_ray = mean(ode_steps);
  out.reference_ms_per_ray = 1e3 * mean(ref_t);
  out.pieces_per_ray = mean(pieces);
  return out;
}

double smooth_field(const Vec3& p) {
  return 0.5 + 0.3 * std::sin(2.0 * p.x() + 1.0) * std::cos(3.0 * p.y()) + 0.2 * p.z() * p.z();
}

// The rays [rays.begin, rays.end) of one voxel grid, in order.
std::vector<VoxelRaySample> sample_voxels(bool random_values, int n, std::uint64_t kind,
                                          const CellsStudyOptions& o, IndexRange rays) {
  std::mt19937_64 grid_rng = sample_rng(o.seed, kind, 0);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const double h = 1.0 / (n - 1);
  std::vector<double> values;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        values.push_back(random_values ? u01(grid_rng) : smooth_field(Vec3(i * h, j * h, k * h)));
  const VoxelGrid grid({n, n, n}, Vec3::Zero(), Vec3::Constant(h), values);
  // A brick covering the unit box, only to draw rays through it.
  const HigherOrderCell box = make_brick(CellType::hex8, Vec3::Constant(0.5),
                                         0.5 * Eigen::Matrix3d::Identity(), std::vector<double>(8, 0.0));
  std::vector<VoxelRaySample> samples(rays.size());
  parallel_for(static_cast<long long>(rays.size()), o.threads, [&](long long item) {
    const auto i = static_cast<std::uint64_t>(rays.begin) + static_cast<std::uint64_t>(item);
    std::mt19937_64 rng = sample_rng(o.seed, kind, i + 1);
    const TransferFunctions tf = random_transfer_functions(rng());
    const ViewRay ray = random_ray_through(box, rng());
    VoxelRaySample& s = samples[static_cast<std::size_t>(item)];
    auto t0 = Clock::now();
    const ReferenceRay ref = reference_poly_ray(tf, trilinear_ray(grid, ray, kBackground));
    s.reference_s = seconds_since(t0);
    const ExactIntegrator exact(tf);
    t0 = Clock::now();
    const Ray linear = ray_segments(grid, ray, kBackground);
    const RayResult r = exact.integrate(linear, nullptr);
    s.exact_s = seconds_since(t0);
    s.segments = static_cast<double>(linear.segments.size());
    s.error = ray_error(r, ref);
  });
  return samples;
}

VoxelResult summarise_voxels(bool random_values, int n, const std::vector<VoxelRaySample>& samples) {
  VoxelResult out;
  out.field = random_values ? "random" : "smooth";
  out.points_per_axis = n;
  out.samples = static_cast<int>(samples.size());
  std::vector<double> err, seg, ex, rf;
  for (const auto& s : samples) {
    err.push_back(s.error);
    seg.push_back(s.segments);
    ex.push_back(s.exact_s);
    rf.push_back(s.reference_s);
  }
  out.rel = error_stats(err);
  out.segments_per_ray = mean(seg);
  out.exact_us_per_ray = 1e6 * mean(ex);
  out.reference_ms_per_ray = 1e3 * mean(rf);
  return out;
}

}  // namespace

HigherOrderCell random_cell(CellType type, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  std::vector<double> values(static_cast<std::size_t>(node_count(type)));
  for (double& v : values) v = u01(rng);
  if (type == CellType::tet10) {
    for (;;) {
      std::array<Vec3, 4> c = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
      for (auto& p : c)
        for (int i = 0; i < 3; ++i) p[i] += 0.4 * (u01(rng) - 0.5);
      Eigen::Matrix3d A;
      for (int i = 0; i < 3; ++i) A.col(i) = c[i + 1] - c[0];
      if (std::abs(A.determinant()) >= 0.05) return make_tet10(c, values);
    }
  }
  Eigen::Matrix3d A = 0.5 * Eigen::Matrix3d::Identity();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) A(i, j) += 0.2 * (u01(rng) - 0.5);
  return make_brick(type, Vec3::Zero(), A, values);
}

TransferFunctions random_transfer_functions(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  auto one = [&](double vmax) {
    const int n = 2 + static_cast<int>(u01(rng) * 4);  // 2..5 points
    std::vector<double> s{0.0, 1.0};
    for (int i = 2; i < n; ++i) s.push_back(u01(rng));
    std::sort(s.begin(), s.end());
    s.erase(std::unique(s.begin(), s.end()), s.end());
    PiecewiseLinear f;
    f.scalar = s;
    for (std::size_t i = 0; i < s.size(); ++i) f.value.push_back(vmax * u01(rng));
    return f;
  };
  TransferFunctions tf;
  for (int c = 0; c < kChannels; ++c) {
    tf.density[c] = one(4.0);
    tf.color[c] = one(1.0);
  }
  return tf;
}

ViewRay random_ray_through(const HigherOrderCell& cell, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  auto interior = [&]() {
    Vec3 xi;
    if (cell.type == CellType::tet10) {  // uniform in the reference tet: sorted uniforms
      std::array<double, 3> u{u01(rng), u01(rng), u01(rng)};
      std::sort(u.begin(), u.end());
      xi = Vec3(u[0], u[1] - u[0], u[2] - u[1]);
    } else {
      xi = Vec3(2 * u01(rng) - 1, 2 * u01(rng) - 1, 2 * u01(rng) - 1);
    }
    return to_world(cell, xi);
  };
  for (;;) {
    const Vec3 a = interior(), b = interior();
    if ((b - a).norm() < 1e-3) continue;
    const Vec3 d = (b - a).normalized();
    return {a - 4.0 * d, d};  // the eye outside the cell (cells are ~1 across)
  }
}

namespace {

void validate(const CellsStudyOptions& o) {
  if (o.count < 1 || o.rays_per_cell < 1 || o.levels.empty() || o.voxel_rays < 1 ||
      o.voxel_random_points < 2)
    throw std::invalid_argument("cells study: count, rays, levels, voxel rays must be >= 1");
  for (int l : o.levels)
    if (l < 1 || l > 64) throw std::invalid_argument("cells study: levels must be in [1, 64]");
  for (int n : o.voxel_sizes)
    if (n < 2 || n > 256) throw std::invalid_argument("cells study: voxel sizes must be in [2, 256]");
}

constexpr CellType kCellTypes[] = {CellType::tet10, CellType::hex8, CellType::hex20};

}  // namespace

CellsSamples run_cells_samples(const CellsStudyOptions& o, const ShardSpec& shard) {
  validate(o);
  const auto t0 = std::chrono::steady_clock::now();
  CellsSamples part;
  std::mutex progress_mutex;
  const IndexRange cells = shard_range(static_cast<std::size_t>(o.count), shard);
  for (CellType type : kCellTypes) part.cells.push_back(sample_cell_type(type, o, cells, progress_mutex));
  const IndexRange rays = shard_range(static_cast<std::size_t>(o.voxel_rays), shard);
  if (o.progress) o.progress("voxels: random values");
  part.voxels.push_back(sample_voxels(true, o.voxel_random_points, 100, o, rays));
  for (int n : o.voxel_sizes) {
    if (o.progress) o.progress("voxels: smooth field, " + std::to_string(n) + " points per axis");
    part.voxels.push_back(sample_voxels(false, n, 200 + static_cast<std::uint64_t>(n), o, rays));
  }
  part.seconds = wall_seconds_since(t0);
  return part;
}

CellsReport finish_cells_study(const CellsStudyOptions& o, const std::vector<CellsSamples>& parts) {
  validate(o);
  const std::size_t n_voxels = 1 + o.voxel_sizes.size();
  for (const CellsSamples& p : parts) {
    if (p.cells.size() != std::size(kCellTypes) || p.voxels.size() != n_voxels)
      throw std::invalid_argument("cells study: a part holds " + std::to_string(p.cells.size()) +
                                  " cell types and " + std::to_string(p.voxels.size()) +
                                  " voxel grids, the run " + std::to_string(std::size(kCellTypes)) +
                                  " and " + std::to_string(n_voxels));
    for (const auto& type : p.cells)
      for (const CellRaySample& s : type)
        if (s.level_error.size() != o.levels.size() || s.level_segments.size() != o.levels.size() ||
            s.level_decompose_s.size() != o.levels.size() || s.level_exact_s.size() != o.levels.size())
          throw std::invalid_argument("cells study: a part's sample has " +
                                      std::to_string(s.level_error.size()) + " levels, the run " +
                                      std::to_string(o.levels.size()));
  }
  CellsReport report;
  report.options = o;
  for (std::size_t t = 0; t < std::size(kCellTypes); ++t) {
    std::vector<CellSample> samples;
    for (const CellsSamples& p : parts) samples.insert(samples.end(), p.cells[t].begin(), p.cells[t].end());
    report.cells.push_back(summarise_cell_type(kCellTypes[t], o, samples));
  }
  for (std::size_t v = 0; v < n_voxels; ++v) {
    std::vector<VoxelRaySample> samples;
    for (const CellsSamples& p : parts) samples.insert(samples.end(), p.voxels[v].begin(), p.voxels[v].end());
    report.voxels.push_back(summarise_voxels(v == 0, v == 0 ? o.voxel_random_points : o.voxel_sizes[v - 1], samples));
  }
  for (const CellsSamples& p : parts) report.seconds += p.seconds;
  return report;
}

CellsReport run_cells_study(const CellsStudyOptions& o) {
  return finish_cells_study(o, {run_cells_samples(o, ShardSpec{})});
}

}  // namespace rayint
