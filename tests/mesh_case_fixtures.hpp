#pragma once
// Mesh test set-ups several tests share.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <utility>

#include "rayint/geometry/camera.hpp"
#include "rayint/integrators/integrator.hpp"
#include "rayint/mesh/mesh_case.hpp"
#include "rayint/mesh/mesh_generators.hpp"
#include "rayint/mesh/tet_traversal.hpp"
#include "rayint/model/ray.hpp"
#include "rayint/studies/mesh_agreement.hpp"

namespace rayint::test {

// A small mesh case the render tests share: the generated ball (generate_mesh("ball", 2, 1)) with
// the agreement transfer functions, seen by a 20 x `height` perspective camera from (0.3, 0.2, 4).
inline MeshCase ball_render_case(int height) {
  MeshCase mc;
  mc.name = "t";
  mc.source = "t.json";
  mc.transfer = agreement_transfer_functions();
  mc.mesh = generate_mesh("ball", 2, 1).mesh;
  Camera cam;
  cam.position = Vec3(0.3, 0.2, 4);
  cam.width = 20;
  cam.height = height;
  cam.fov_deg = 35;
  mc.camera = cam;
  mc.background = {0.1, 0.1, 0.2};
  return mc;
}

// ball_render_case with what a render of it takes: the traversal of its mesh and the exact and
// riemann:n=4 integrators of its transfer functions (they keep a reference to them: not copied).
struct BallRender {
  MeshCase mc;
  TetTraversal mesh;
  std::unique_ptr<RayIntegrator> exact, riemann;
  explicit BallRender(int height)
      : mc(ball_render_case(height)),
        mesh(mc.mesh, "ball"),
        exact(make_integrator(parse_method_spec("exact"), mc.transfer)),
        riemann(make_integrator(parse_method_spec("riemann:n=4"), mc.transfer)) {}
  BallRender(const BallRender&) = delete;
  BallRender& operator=(const BallRender&) = delete;
};

// The chord of [-1,1]^3 (the reader and format fixtures' box) along the ray, in units of its
// normalized direction: [t0, t1] (t1 <= t0 when the ray misses). Slab clipping written out here,
// independent of the library's.
inline std::pair<double, double> cube_chord(const ViewRay& r) {
  const Vec3 d = r.direction.normalized();
  double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0.0) {
      if (std::fabs(r.origin[k]) > 1.0) t1 = -1.0;
      continue;
    }
    double a = (-1.0 - r.origin[k]) / d[k], b = (1.0 - r.origin[k]) / d[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  return {t0, t1};
}

// The reader and format fixtures' linear field.
inline double linear_field(const Vec3& p) { return 0.5 + 0.3 * p.x() - 0.2 * p.y() + 0.4 * p.z(); }

// The analytic ray of the linear field: one segment through [-1,1]^3 (cube_chord), the field's
// values at its ends, far end first.
inline Ray analytic_linear_ray(const ViewRay& r, const Rgb& background) {
  const Vec3 d = r.direction.normalized();
  const auto [t0, t1] = cube_chord(r);
  Ray ray;
  ray.background = background;
  if (t1 > t0) ray.segments.push_back({t1 - t0, linear_field(r.origin + t1 * d), linear_field(r.origin + t0 * d)});
  return ray;
}

// A transfer function with breakpoints inside the range of the fixtures' linear field, so rays
// cross several pieces (the mesh format and repair tests).
inline TransferFunctions mesh_field_tf() {
  TransferFunctions tf;
  tf.density = {PiecewiseLinear{{-0.5, 0.4, 1.5}, {0.2, 1.6, 0.4}},
                PiecewiseLinear{{-0.5, 1.5}, {0.9, 0.3}}, PiecewiseLinear{{0.0}, {0.7}}};
  tf.color = {PiecewiseLinear{{-0.5, 1.5}, {0.1, 0.9}}, PiecewiseLinear{{0.0, 1.0}, {0.8, 0.2}},
              PiecewiseLinear{{0.0}, {0.5}}};
  return tf;
}

// The points, point scalars and tets of `a` and then of `b`, b's indices moved past a's points (no
// shared points; cell scalars are not carried).
inline TetMesh concat(TetMesh a, const TetMesh& b) {
  const auto offset = static_cast<std::int32_t>(a.points.size());
  a.points.insert(a.points.end(), b.points.begin(), b.points.end());
  a.scalars.insert(a.scalars.end(), b.scalars.begin(), b.scalars.end());
  for (auto t : b.tets) {
    for (auto& i : t) i += offset;
    a.tets.push_back(t);
  }
  return a;
}

}  // namespace rayint::test
