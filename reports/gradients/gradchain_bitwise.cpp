// gradchain_bitwise.cpp -- the check behind reports/gradients/README.md, "Per ray: the chain's
// bookkeeping rewritten": every entry of exact_ray_gradient (all blocks, and
// GradientBlocks::segments) and of psi_table_ray_gradient (size 64, nearest and linear: the chain's
// PieceEnds::moving) printed as the hex of its double, over 1800 rays: 30 rays of each stress
// regime (seed 2828, cut to 300 segments; gradchain_rays.hpp), each in 4 variants -- as sampled; with a jump inserted
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
#include "gradchain_rays.hpp"
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
  int rays = 0;
  for_each_ray([&](int n, const RaySample& v) {
    dump_ray_gradients(n, v, dump);
    rays = n + 1;
  });
  std::fprintf(stderr, "rays %d hash %016llx\n", rays, h);
}
