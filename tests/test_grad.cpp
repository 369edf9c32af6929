// Exact gradients of the ray integral (issue 28): integrators/exact_grad.* against the 50-digit
// reference gradient (reference/reference_grad.*), over the case corpus and the stress regimes.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "rayint/generators/regimes.hpp"
#include "rayint/input/case_reader.hpp"
#include "rayint/integrators/exact.hpp"
#include "rayint/integrators/exact_grad.hpp"
#include "rayint/reference/reference_grad.hpp"
#include "tolerances.hpp"

using namespace rayint;

namespace {

// Max over entries of |got - want| / (largest |want| entry of the channel), per channel; the
// worst entry is named in `where`.
double gradient_error(const RayGradient& got, const RayGradient& want, int c, std::string* where) {
  const double scale = want.channel_scale(c);
  std::vector<double> w;
  want.for_each(c, [&w](double v, const char*, std::size_t, const char*) { w.push_back(v); });
  std::size_t i = 0;
  double worst = 0.0;
  got.for_each(c, [&](double v, const char* block, std::size_t idx, const char* param) {
    const double diff = std::fabs(v - w[i++]);
    const double e = scale > 0.0 ? diff / scale : diff;
    if (!(e <= worst)) {
      worst = e;
      if (where) *where = std::string(block) + "[" + std::to_string(idx) + "]" + (*param ? "." : "") + param;
    }
  });
  return worst;
}

struct Worst {
  double err = 0.0;
  std::string where;
  long samples = 0;
  void add(const RayGradient& got, const RayGradient& want, const std::string& label) {
    for (int c = 0; c < kChannels; ++c) {
      std::string w;
      const double e = gradient_error(got, want, c, &w);
      ++samples;
      if (!(e <= err)) {
        err = e;
        where = label + " channel " + std::to_string(c) + " " + w;
      }
    }
  }
};

}  // namespace

TEST_CASE("exact gradient: forward intensity is exact:path=scalar's, bit for bit", "[grad]") {
  const Case cs = read_case_file(RAYINT_SOURCE_DIR "/cases/medical-ct.json");
  ExactIntegrator scalar(cs.transfer, ExactIntegrator::Path::scalar);
  for (const Ray& ray : cs.rays) {
    const RayGradient g = exact_ray_gradient(cs.transfer, ray);
    const RayResult r = scalar.integrate(ray, nullptr);
    for (int c = 0; c < kChannels; ++c) CHECK(g.intensity[c] == r.intensity[c]);
  }
}

TEST_CASE("exact gradient against the 50-digit reference: piece regimes", "[grad]") {
  std::mt19937_64 rng(28);
  Worst all;
  for (const Regime r : all_regimes()) {
    Worst wr;
    for (int i = 0; i < 40; ++i) {
      const RaySample s = sample_ray(r, rng);
      const RayGradient got = exact_ray_gradient(s.transfer, s.ray);
      const ReferenceGradient ref = reference_gradient(s.transfer, s.ray);
      wr.add(got, ref.gradient, regime_name(r) + " #" + std::to_string(i));
    }
    WARN(regime_name(r) << ": worst " << wr.err << " at " << wr.where << " (" << wr.samples << " channels)");
    CHECK(wr.err <= test::GradTolerances::exact_vs_reference_rel);
    all.err = std::max(all.err, wr.err);
  }
}

TEST_CASE("exact gradient against the 50-digit reference: case corpus", "[grad]") {
  Worst w;
  for (const std::string& file : list_case_files(RAYINT_SOURCE_DIR "/cases")) {
    if (file.find("/mesh-") != std::string::npos || file.find("gates.json") != std::string::npos) continue;
    const Case cs = read_case_file(file);
    for (std::size_t i = 0; i < cs.rays.size(); ++i) {
      const RayGradient got = exact_ray_gradient(cs.transfer, cs.rays[i]);
      const ReferenceGradient ref = reference_gradient(cs.transfer, cs.rays[i]);
      w.add(got, ref.gradient, cs.name + " ray " + std::to_string(i));
    }
  }
  WARN("corpus: worst " << w.err << " at " << w.where << " (" << w.samples << " ray-channels)");
  CHECK(w.err <= test::GradTolerances::exact_vs_reference_rel);
}

TEST_CASE("exact gradient: kink convention at a constant-scalar segment on a node", "[grad]") {
  // density slopes 4 left of 0.5 and -6 right of it; one segment of constant scalar s.
  TransferFunctions tf;
  for (int c = 0; c < kChannels; ++c) {
    tf.density[c] = {{0.0, 0.5, 1.0}, {1.0, 3.0, 0.0}};
    tf.color[c] = {{0.0, 1.0}, {0.6, 0.6}};
  }
  const auto at = [&](double s) {
    Ray ray;
    ray.segments = {{0.7, s, s}};
    return ray;
  };
  const RayGradient on = exact_ray_gradient(tf, at(0.5));
  const RayGradient right = exact_ray_gradient(tf, at(0.5 + 1e-9));
  const RayGradient left = exact_ray_gradient(tf, at(0.5 - 1e-9));
  // The documented side: the interval to the right of the node.
  for (int c = 0; c < kChannels; ++c) {
    CHECK(std::fabs(on.scalar_far[0][c] - right.scalar_far[0][c]) <= 1e-7 * std::fabs(right.scalar_far[0][c]));
    CHECK(std::fabs(on.density[c][1].position - right.density[c][1].position) <=
          1e-7 * std::fabs(right.density[c][1].position));
    // ... and not the left one: the slopes differ in sign.
    CHECK(on.scalar_far[0][c] * left.scalar_far[0][c] < 0.0);  // colour constant: only rho moves
  }
  // The reference takes the same side by its one-sided stencils.
  const ReferenceGradient ref = reference_gradient(tf, at(0.5));
  for (int c = 0; c < kChannels; ++c) CHECK(gradient_error(on, ref.gradient, c, nullptr) <= 1e-15);
}
