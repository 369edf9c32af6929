// gradbatch_compare.cpp -- the check behind reports/gradients/README.md, "Per ray: the piece
// derivatives through the SIMD batch" (branch grad28cost): on gradchain_bitwise.cpp's 1800 rays
// (gradchain_rays.hpp: 30 of each stress regime, seed 2828, cut to 300 segments, each as sampled, with jumps, with
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
#include "gradchain_rays.hpp"
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
  int rays = 0;
  for_each_ray([&](int n, const RaySample& v) {
    try {
      const RayResult rb = ExactIntegrator(v.transfer).integrate(v.ray, nullptr);
      const RayResult rs = ExactIntegrator(v.transfer, ExactIntegrator::Path::scalar).integrate(v.ray, nullptr);
      for (int c = 0; c < 3; ++c) std::printf("F %d %016llx %016llx\n", c, hx(rb.intensity[c]), hx(rs.intensity[c]));
    } catch (std::exception& e) { std::printf("E %s\n", e.what()); }
    dump_ray_gradients(n, v, dump);
    rays = n + 1;
  });
  std::fprintf(stderr, "rays %d\n", rays);
}
