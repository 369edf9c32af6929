// Cell, vertex-averaged and inverse-distance-weighted gradients (Williams & Max Sec. 3.2; see
// gradients.hpp).
#include "rayint/mesh/gradients.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>
#include <stdexcept>

namespace rayint {

std::string gradient_mode_name(GradientMode mode) {
  switch (mode) {
    case GradientMode::cell: return "cell";
    case GradientMode::vertex_average: return "vertex_average";
    case GradientMode::inverse_distance: return "inverse_distance";
  }
  return "cell";
}

GradientMode parse_gradient_mode(const std::string& name) {
  if (name == "cell") return GradientMode::cell;
  if (name == "vertex_average") return GradientMode::vertex_average;
  if (name == "inverse_distance") return GradientMode::inverse_distance;
  throw std::invalid_argument("must be \"cell\", \"vertex_average\" or \"inverse_distance\", got \"" + name + "\"");
}

bool well_conditioned_by_norms(double det, const Vec3& a, const Vec3& b, const Vec3& c) {
  return std::isfinite(det) && std::fabs(det) > kSolveVolumeRatio * a.norm() * b.norm() * c.norm();
}

TetFrame tet_frame(const TetMesh& mesh, std::size_t cell) {
  const auto& t = mesh.tets[cell];
  TetFrame f;
  f.x0 = mesh.points[t[0]];
  f.e1 = mesh.points[t[1]] - f.x0, f.e2 = mesh.points[t[2]] - f.x0, f.e3 = mesh.points[t[3]] - f.x0;
  f.c23 = f.e2.cross(f.e3);
  f.det = f.e1.dot(f.c23);
  f.cramer = well_conditioned(f.det, f.e1, f.e2, f.e3);
  return f;
}

std::array<double, 4> barycentric(const TetFrame& f, const Vec3& p) {
  const Vec3 r = p - f.x0;
  if (f.cramer) {
    const double l1 = r.dot(f.c23) / f.det, l2 = f.e1.dot(r.cross(f.e3)) / f.det, l3 = f.e1.dot(f.e2.cross(r)) / f.det;
    return {1.0 - l1 - l2 - l3, l1, l2, l3};
  }
  Eigen::Matrix3d e;
  e.col(0) = f.e1, e.col(1) = f.e2, e.col(2) = f.e3;
  const Vec3 l = e.fullPivLu().solve(r);
  return {1.0 - l[0] - l[1] - l[2], l[0], l[1], l[2]};
}

GradientField::GradientField(const TetTraversal& mesh, GradientMode mode) : mesh_(&mesh), mode_(mode) {
  if (mode == GradientMode::cell) return;
  const TetMesh& m = mesh.mesh();
  vertex_.assign(m.points.size(), Vec3::Zero());
  std::vector<double> weight(m.points.size(), 0.0);
  for (std::size_t c = 0; c < m.tets.size(); ++c) {
    Vec3 centroid = Vec3::Zero();
    for (auto i : m.tets[c]) centroid += m.points[i];
    centroid /= 4.0;
    const Vec3& g = mesh.gradient(c);
    for (auto i : m.tets[c]) {
      const double wgt = mode == GradientMode::vertex_average ? 1.0 : 1.0 / (centroid - m.points[i]).norm();
      vertex_[i] += wgt * g;
      weight[i] += wgt;
    }
  }
  for (std::size_t i = 0; i < vertex_.size(); ++i)
    if (weight[i] > 0.0) vertex_[i] /= weight[i];
}

Vec3 GradientField::at(std::size_t cell, const Vec3& p) const {
  if (mode_ == GradientMode::cell) return mesh_->gradient(cell);
  const auto l = barycentric(mesh_->mesh(), cell, p);
  Vec3 g = Vec3::Zero();
  for (std::size_t k = 0; k < 4; ++k) g += l[k] * vertex_[mesh_->mesh().tets[cell][k]];
  return g;
}

}  // namespace rayint
