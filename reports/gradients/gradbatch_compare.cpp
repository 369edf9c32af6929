// gradbatch_compare.cpp -- the check behind reports/gradients/README.md, "Per ray: the piece
// derivatives through the SIMD batch" (branch grad28cost): on gradchain_bitwise.cpp's 1800 rays
// (30 of each stress regime, seed 2828, cut to 300 segments, each as sampled, with jumps, with
// ends and constant segments on breakpoints and reversed segments, and as a grey medium), every
// entry of exact_ray_gradient (all blocks and GradientBlocks::segments) and of
// psi_table_ray_gradient (size 64, nearest and linear) as "channel hex" lines, and per ray the
// forward intensities of ExactIntegrator's batch and scalar paths ("F channel batch scalar").
// gradbatch_compare.py compares two builds' outputs entry by entry, relative to each channel's
// largest entry. Build against a build tree as gradchain_bitwise.cpp:
//   B=build; g++ -O2 -std=c++17 $(for d in $B/src/area-include/*; do printf ' -I%s' $d; done) \
//     reports/gradients/gradbatch_compare.cpp -o compare \
//     -Wl,--start-group $B/src/librayint_*.a -Wl,--end-group -lhwy -lcerf -ltbb -lpthread
// Not part of the build or the tests: a one-off comparison of two versions of the same code.
#include <cstdio>
#include <cstring>
#include <cstdint>
#include <random>
#include <algorithm>
#include "rayint/generators/regimes.hpp"
#include "rayint/integrators/exact_grad.hpp"
#include "rayint/integrators/psi_table_grad.hpp"
#include "rayint/integrators/exact.hpp"
using namespace rayint;
static unsigned long long hx(double v) { std::uint64_t u; std::memcpy(&u, &v, 8); return (unsigned long long)u; }
static void put(int c, double v) { std::printf("%d %016llx\n", c, hx(v)); }
static void dump(const RayGradient& g) {
  for (int c = 0; c < 3; ++c) std::printf("I %d %016llx\n", c, hx(g.intensity[c]));
  for (int c = 0; c < 3; ++c) put(c, g.background[c]);
  for (auto* b : {&g.length, &g.scalar_far, &g.scalar_exit}) for (auto& v : *b) for (int c = 0; c < 3; ++c) put(c, v[c]);
  for (int c = 0; c < 3; ++c) for (auto* n : {&g.density[c], &g.color[c]}) for (auto& d : *n) { put(c, d.position); put(c, d.value); }
  std::printf("U %s\n", g.undefined.c_str());
}
int main() {
  std::mt19937_64 rng(2828);
  int n = 0;
  for (const Regime r : stress_regimes())
    for (int i = 0; i < 30; ++i) {
      RaySample rs = sample_ray(r, rng);
      if (rs.ray.segments.size() > 300) rs.ray.segments.resize(300);
      for (int variant = 0; variant < 4; ++variant) {
        RaySample v = rs;
        std::uniform_real_distribution<double> U(0, 1);
        if (variant >= 1) {  // jumps: duplicate a node in some functions with a new value
          for (int c = 0; c < 3; ++c) for (auto* f : {&v.transfer.density[c], &v.transfer.color[c]}) {
            if (f->scalar.size() < 2 || U(rng) < 0.4) continue;
            std::size_t k = rng() % f->scalar.size();
            if ((k > 0 && f->scalar[k-1] == f->scalar[k]) || (k + 1 < f->scalar.size() && f->scalar[k+1] == f->scalar[k])) continue;
            f->scalar.insert(f->scalar.begin() + k + 1, f->scalar[k]);
            f->value.insert(f->value.begin() + k + 1, f->value[k] * (0.5 + U(rng)) + 0.1);
          }
          if (variant == 3) v.transfer.density[1] = v.transfer.density[2] = v.transfer.density[0];
        }
        if (variant >= 2) {  // ends on nodes, constant segments on nodes, descending segments
          std::vector<double> bp = v.transfer.breakpoints();
          for (auto& s : v.ray.segments) {
            double x = U(rng);
            if (x < 0.1) s.scalar_far = bp[rng() % bp.size()];
            else if (x < 0.2) s.scalar_exit = bp[rng() % bp.size()];
            else if (x < 0.25) s.scalar_far = s.scalar_exit = bp[rng() % bp.size()];
            else if (x < 0.3) s.scalar_exit = s.scalar_far;
            else if (x < 0.4) std::swap(s.scalar_far, s.scalar_exit);
          }
        }
        RayGradient g;
        try {
          const RayResult rb = ExactIntegrator(v.transfer).integrate(v.ray, nullptr);
          const RayResult rs = ExactIntegrator(v.transfer, ExactIntegrator::Path::scalar).integrate(v.ray, nullptr);
          for (int c = 0; c < 3; ++c) std::printf("F %d %016llx %016llx\n", c, hx(rb.intensity[c]), hx(rs.intensity[c]));
        } catch (std::exception& e) { std::printf("E %s\n", e.what()); }
        try { std::printf("G %d full\n", n); exact_ray_gradient(v.transfer, v.ray, g); dump(g); } catch (std::exception& e) { std::printf("E %s\n", e.what()); }
        try { std::printf("G %d seg\n", n); exact_ray_gradient(v.transfer, v.ray, g, GradientBlocks::segments); dump(g); } catch (std::exception& e) { std::printf("E %s\n", e.what()); }
        if (v.ray.segments.size() <= 60)
          for (auto lk : {table::Lookup::nearest, table::Lookup::linear})
            try { std::printf("G %d psi\n", n); dump(psi_table_ray_gradient(v.transfer, v.ray, 64, lk)); } catch (std::exception& e) { std::printf("E %s\n", e.what()); }
        ++n;
      }
    }
  std::fprintf(stderr, "rays %d\n", n);
}
