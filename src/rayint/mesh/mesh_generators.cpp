// Generated meshes with analytic fields (see mesh_generators.hpp).
#include "rayint/mesh/mesh_generators.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

namespace rayint {

TetMesh structured_box_mesh(const Vec3& lo, const Vec3& hi, int nx, int ny, int nz) {
  TetMesh m;
  const auto id = [&](int i, int j, int k) { return static_cast<std::int32_t>((k * (ny + 1) + j) * (nx + 1) + i); };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        const Vec3 u(double(i) / nx, double(j) / ny, double(k) / nz);
        // Exact end points: the box faces are the planes lo and hi, whatever the rounding.
        Vec3 p = lo + u.cwiseProduct(hi - lo);
        if (i == nx) p.x() = hi.x();
        if (j == ny) p.y() = hi.y();
        if (k == nz) p.z() = hi.z();
        m.points.push_back(p);
      }
  m.scalars.assign(m.points.size(), 0.0);
  static const int kPerm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (const auto& perm : kPerm) {
          int b[3] = {0, 0, 0};
          std::array<std::int32_t, 4> t{};
          t[0] = id(i, j, k);
          for (std::size_t s = 0; s < 3; ++s) {
            b[perm[s]] = 1;
            t[s + 1] = id(i + b[0], j + b[1], k + b[2]);
          }
          m.tets.push_back(t);
        }
  reorient_tets(m);
  return m;
}

TetMesh keep_tets(const TetMesh& mesh, const std::function<bool(const Vec3&)>& keep) {
  TetMesh out;
  std::vector<std::int32_t> remap(mesh.points.size(), -1);
  for (const auto& t : mesh.tets) {
    Vec3 c = Vec3::Zero();
    for (auto i : t) c += mesh.points[i];
    if (!keep(c / 4.0)) continue;
    std::array<std::int32_t, 4> nt{};
    for (std::size_t k = 0; k < 4; ++k) {
      auto& r = remap[t[k]];
      if (r < 0) {
        r = static_cast<std::int32_t>(out.points.size());
        out.points.push_back(mesh.points[t[k]]);
        out.scalars.push_back(mesh.scalars[t[k]]);
      }
      nt[k] = r;
    }
    out.tets.push_back(nt);
  }
  return out;
}

void assign_field(TetMesh& mesh, const std::function<double(const Vec3&)>& field) {
  mesh.scalars.resize(mesh.points.size());
  for (std::size_t i = 0; i < mesh.points.size(); ++i) mesh.scalars[i] = field(mesh.points[i]);
}

void jitter_interior(TetMesh& mesh, const Vec3& lo, const Vec3& hi, int n, double fraction,
                     std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Vec3 h = (hi - lo) / n;
  for (Vec3& p : mesh.points) {
    bool boundary = false;
    for (int k = 0; k < 3; ++k) boundary = boundary || p[k] == lo[k] || p[k] == hi[k];
    const Vec3 delta(u(rng), u(rng), u(rng));
    if (!boundary) p += fraction * delta.cwiseProduct(h);
  }
}

std::vector<std::string> generated_mesh_kinds() { return {"ball", "linear-box", "ring"}; }

GeneratedMesh generate_mesh(const std::string& kind, int n, std::uint64_t seed) {
  if (n < 1 || n > 200) throw std::invalid_argument("--n must be in [1, 200], got " + std::to_string(n));
  GeneratedMesh g;
  const std::string cmd = "rayint generate-mesh " + kind + " --n " + std::to_string(n);
  if (kind == "ball") {
    // The cube [-1,1]^3 (2n cells per edge) mapped onto the unit ball by p -> p |p|_inf / |p|_2,
    // which sends each cube shell to a sphere; s = 1 - |x| (radial).
    g.mesh = structured_box_mesh(Vec3(-1, -1, -1), Vec3(1, 1, 1), 2 * n, 2 * n, 2 * n);
    for (Vec3& p : g.mesh.points) {
      const double r2 = p.norm();
      if (r2 > 0.0) p *= p.cwiseAbs().maxCoeff() / r2;
    }
    reorient_tets(g.mesh);
    assign_field(g.mesh, [](const Vec3& p) { return 1.0 - p.norm(); });
    g.description = "unit ball, " + std::to_string(g.mesh.tets.size()) + " tets, radial field s = 1 - |x|";
  } else if (kind == "linear-box") {
    const Vec3 lo(-1, -1, -1), hi(1, 1, 1);
    g.mesh = structured_box_mesh(lo, hi, 2 * n, 2 * n, 2 * n);
    jitter_interior(g.mesh, lo, hi, 2 * n, 0.15, seed);
    assign_field(g.mesh, [](const Vec3& p) { return 0.5 + 0.3 * p.x() - 0.2 * p.y() + 0.4 * p.z(); });
    g.description = "box [-1,1]^3 with jittered interior points (seed " + std::to_string(seed) + "), " +
                    std::to_string(g.mesh.tets.size()) + " tets, linear field s = 0.5 + 0.3x - 0.2y + 0.4z";
  } else if (kind == "ring") {
    // 10n cells per axis over [-1,1] in x, y (h = 0.2/n: the hole edge 0.4 lies on grid lines), n in z.
    g.mesh = structured_box_mesh(Vec3(-1, -1, -0.25), Vec3(1, 1, 0.25), 10 * n, 10 * n, n);
    g.mesh = keep_tets(g.mesh, [](const Vec3& c) { return std::max(std::fabs(c.x()), std::fabs(c.y())) > 0.4; });
    assign_field(g.mesh, [](const Vec3& p) { return std::sqrt(p.x() * p.x() + p.y() * p.y()); });
    g.description = "square ring [-1,1]^2 x [-0.25,0.25] minus the hole |x|,|y| < 0.4 (non-convex), " +
                    std::to_string(g.mesh.tets.size()) + " tets, field s = sqrt(x^2 + y^2)";
  } else {
    throw std::invalid_argument("unknown mesh kind \"" + kind + "\" (ball, linear-box, ring)");
  }
  g.description += "; generated by `" + cmd + (kind == "linear-box" ? " --seed " + std::to_string(seed) : "") +
                   "`, do not edit";
  validate_tet_mesh(g.mesh, kind);
  return g;
}

}  // namespace rayint
