// Mesh path vs. single segment on a globally linear field (see mesh_agreement.hpp).
#include "rayint/studies/mesh_agreement.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "rayint/integrators/integrator.hpp"
#include "rayint/mesh/mesh_generators.hpp"
#include "rayint/mesh/tet_traversal.hpp"

namespace rayint {

TransferFunctions agreement_transfer_functions() {
  TransferFunctions tf;
  const PiecewiseLinear density{{-0.5, 0.2, 0.7, 1.2}, {0.5, 3.0, 0.2, 5.0}};
  tf.density = {density, density, density};
  tf.color = {PiecewiseLinear{{-0.4, 0.5, 1.3}, {1.0, 0.2, 1.5}}, PiecewiseLinear{{0.0, 1.0}, {0.1, 1.0}},
              PiecewiseLinear{{-0.2, 0.4, 0.9}, {0.4, 1.2, 0.6}}};
  return tf;
}

MeshAgreement measure_linear_field_agreement(const MeshAgreementOptions& o) {
  const GeneratedMesh g = generate_mesh("linear-box", o.n, 1);
  const auto field = [](const Vec3& p) { return 0.5 + 0.3 * p.x() - 0.2 * p.y() + 0.4 * p.z(); };
  const TetTraversal mesh(g.mesh, "linear-box");
  const TransferFunctions tf = agreement_transfer_functions();
  const auto exact = make_integrator(parse_method_spec("exact"), tf);
  MeshAgreement a;
  a.tets = static_cast<long>(g.mesh.tets.size());
  std::mt19937_64 rng(o.seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uni(-1.2, 1.2);
  const Rgb background{0.2, 0.1, 0.05};
  TraversalStats stats;
  for (int i = 0; i < o.rays; ++i) {
    Vec3 o_dir(normal(rng), normal(rng), normal(rng));
    const Vec3 origin = 4.0 * o_dir.normalized();
    const Vec3 target(uni(rng), uni(rng), uni(rng));
    const ViewRay vr{origin, (target - origin).normalized()};
    RayTrace trace;
    mesh.trace(vr, trace, &stats);
    const Ray mesh_path = ray_from_trace(trace, background);
    ++a.rays;
    // The single segment, from where the walk entered the mesh to where it left it, with the
    // analytic field at both ends: what the mesh path would be without cells.
    Ray single;
    single.background = background;
    if (!trace.crossings.empty()) {
      const double t_first = trace.crossings.front().t_in, t_last = trace.crossings.back().t_out;
      single.segments.push_back(Segment{t_last - t_first, field(trace.origin + t_last * trace.direction),
                                        field(trace.origin + t_first * trace.direction)});
      ++a.hits;
    }
    // Geometry, separately: the total length inside against the ray's chord through the box
    // [-1,1]^3 (slabs; the box boundary is not jittered). This is an absolute error: for a ray
    // that clips a corner, the relative error of a 1e-3 chord is ~1e3 times larger.
    double t0 = -std::numeric_limits<double>::infinity(), t1 = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
      double lo = (-1.0 - vr.origin[k]) / vr.direction[k], hi = (1.0 - vr.origin[k]) / vr.direction[k];
      if (lo > hi) std::swap(lo, hi);
      t0 = std::max(t0, lo);
      t1 = std::min(t1, hi);
    }
    const double chord = t1 > t0 ? t1 - t0 : 0.0;
    double length = 0.0;
    for (const Segment& s : mesh_path.segments) length += s.length;
    a.segments += static_cast<long>(mesh_path.segments.size());
    a.max_length_abs = std::max(a.max_length_abs, std::fabs(length - chord));
    const RayResult rm = exact->integrate(mesh_path, nullptr);
    const RayResult rs = exact->integrate(single, nullptr);
    for (int ch = 0; ch < kChannels; ++ch) {
      const double ref = rs.intensity[ch];
      const double err = std::fabs(rm.intensity[ch] - ref) / std::fabs(ref);
      a.max_rel = std::max(a.max_rel, std::isfinite(err) ? err : std::numeric_limits<double>::infinity());
    }
  }
  a.budget_exhausted = stats.budget_exhausted;
  return a;
}

VertexRayChords measure_vertex_ray_chords(int n, int rays, std::uint64_t seed) {
  const TetTraversal mesh(structured_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), n, n, n), "cube");
  VertexRayChords v;
  v.tets = static_cast<long>(mesh.cell_count());
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> idx(0, n);
  TraversalStats stats;
  for (int i = 0; i < rays; ++i) {
    Vec3 a(idx(rng), idx(rng), idx(rng)), b(idx(rng), idx(rng), idx(rng));
    a /= n;
    b /= n;
    bool tangent = a == b;
    for (int k = 0; k < 3; ++k) tangent = tangent || (a[k] == b[k] && (a[k] == 0.0 || a[k] == 1.0));
    if (tangent) continue;
    const Vec3 d = (b - a).normalized();
    const Vec3 o = a - 3.0 * d;
    double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
      if (d[k] == 0.0) continue;
      double lo = (0.0 - o[k]) / d[k], hi = (1.0 - o[k]) / d[k];
      if (lo > hi) std::swap(lo, hi);
      t0 = std::max(t0, lo);
      t1 = std::min(t1, hi);
    }
    double length = 0.0;
    for (const Segment& s : mesh_ray(mesh, ViewRay{o, d}, Rgb{0, 0, 0}, &stats).segments) length += s.length;
    v.max_length_abs = std::max(v.max_length_abs, std::fabs(length - std::max(0.0, t1 - t0)));
    ++v.rays;
  }
  v.zero_length_steps = stats.zero_length_steps;
  v.star_searches = stats.star_searches;
  v.budget_exhausted = stats.budget_exhausted;
  return v;
}

}  // namespace rayint
