// gradchain_bitwise.cpp -- the check behind reports/gradients/README.md, "Per ray: the chain's
// bookkeeping rewritten": every entry of exact_ray_gradient (all blocks, and
// GradientBlocks::segments) and of psi_table_ray_gradient (size 64, nearest and linear: the chain's
// PieceEnds::moving) printed as the hex of its double, over 1800 rays: 30 rays of each stress
// regime (seed 2828, cut to 300 segments), each in 4 variants -- as sampled; with a jump inserted
// in 60% of the functions; plus segment ends put on breakpoints, constant segments on
// breakpoints, constant and reversed segments; plus a grey medium (three densities equal). Build
// against a build tree and compare two builds' outputs with cmp (stderr: the FNV-1a hash):
//   B=build; g++ -O2 -std=c++17 $(for d in $B/src/area-include/*; do printf ' -I%s' $d; done) \
//     reports/gradients/gradchain_bitwise.cpp -o bitwise \
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
using namespace rayint;
static unsigned long long h = 1469598103934665603ull;
static void put(double v) { std::uint64_t u; std::memcpy(&u, &v, 8); h = (h ^ u) * 1099511628211ull; std::printf("%016llx\n", (unsigned long long)u); }
static void dump(const RayGradient& g) {
  for (int c = 0; c < 3; ++c) { put(g.intensity[c]); put(g.background[c]); }
  for (auto* b : {&g.length, &g.scalar_far, &g.scalar_exit}) for (auto& v : *b) for (int c = 0; c < 3; ++c) put(v[c]);
  for (int c = 0; c < 3; ++c) for (auto* n : {&g.density[c], &g.color[c]}) for (auto& d : *n) { put(d.position); put(d.value); }
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
        try { std::printf("G %d full\n", n); exact_ray_gradient(v.transfer, v.ray, g); dump(g); } catch (std::exception& e) { std::printf("E %s\n", e.what()); }
        try { std::printf("G %d seg\n", n); exact_ray_gradient(v.transfer, v.ray, g, GradientBlocks::segments); dump(g); } catch (std::exception& e) { std::printf("E %s\n", e.what()); }
        if (v.ray.segments.size() <= 60)
          for (auto lk : {table::Lookup::nearest, table::Lookup::linear})
            try { std::printf("G %d psi\n", n); dump(psi_table_ray_gradient(v.transfer, v.ray, 64, lk)); } catch (std::exception& e) { std::printf("E %s\n", e.what()); }
        ++n;
      }
    }
  std::fprintf(stderr, "rays %d hash %016llx\n", n, h);
}
