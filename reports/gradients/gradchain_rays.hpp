// gradchain_rays.hpp -- the 1800 rays of gradchain_bitwise.cpp and gradbatch_compare.cpp (one-off
// comparison tools of reports/gradients, not part of the build): 30 rays of each stress regime
// (seed 2828, cut to 300 segments), each in 4 variants -- as sampled; with a jump inserted in 60%
// of the functions; plus segment ends put on breakpoints, constant segments on breakpoints,
// constant and reversed segments; plus a grey medium (three densities equal).
// for_each_ray(visit) calls visit(n, ray_sample) for n = 0..1799, in order; dump_ray_gradients
// prints the gradients both tools compare for one ray.
#pragma once
#include <algorithm>
#include <cstdio>
#include <exception>
#include <random>
#include <vector>
#include "rayint/generators/regimes.hpp"
#include "rayint/integrators/exact_grad.hpp"
#include "rayint/integrators/psi_table_grad.hpp"

template <class F>
void for_each_ray(F&& visit) {
  using namespace rayint;
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
        visit(n, static_cast<const RaySample&>(v));
        ++n;
      }
    }
}

// Ray n's gradients, each after a line "G n KIND" and printed by dump(gradient): exact_ray_gradient
// with every block (KIND full) and GradientBlocks::segments (seg), and on rays of at most 60
// segments psi_table_ray_gradient of size 64, nearest then linear (psi). A throw prints "E what".
template <class Dump>
void dump_ray_gradients(int n, const rayint::RaySample& v, Dump&& dump) {
  using namespace rayint;
  RayGradient g;
  try { std::printf("G %d full\n", n); exact_ray_gradient(v.transfer, v.ray, g); dump(g); } catch (std::exception& e) { std::printf("E %s\n", e.what()); }
  try { std::printf("G %d seg\n", n); exact_ray_gradient(v.transfer, v.ray, g, GradientBlocks::segments); dump(g); } catch (std::exception& e) { std::printf("E %s\n", e.what()); }
  if (v.ray.segments.size() <= 60)
    for (auto lk : {table::Lookup::nearest, table::Lookup::linear})
      try { std::printf("G %d psi\n", n); dump(psi_table_ray_gradient(v.transfer, v.ray, 64, lk)); } catch (std::exception& e) { std::printf("E %s\n", e.what()); }
}
