// The chain rule from a ray's gradient to the mesh's vertex scalars and positions; the formulas
// and their domains are in mesh_gradient.hpp.
#include "rayint/render/mesh_gradient.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "rayint/core/parallel.hpp"
#include "rayint/integrators/exact_grad.hpp"
#include "rayint/mesh/gradients.hpp"

namespace rayint {
namespace {

// Calls sink.scalar(index, Rgb) and sink.position(point, std::array<Rgb, 3>) for every
// contribution of the ray's segment ends; returns how many ends lie on an edge or vertex.
template <class Sink>
long chain_trace(const TetTraversal& traversal, const RayTrace& trace, const RayGradient& g, Sink& sink,
                 bool positions = true) {
  const TetMesh& mesh = traversal.mesh();
  const bool on_cells = !mesh.cell_scalars.empty();
  const std::size_t n = trace.crossings.size();
  long on_edges = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const CellCrossing& x = trace.crossings[i];
    const std::size_t j = n - 1 - i;  // the segment of this crossing (segments run far -> near)
    const auto cell = static_cast<std::size_t>(x.cell);
    const auto& tet = mesh.tets[cell];
    const TetFrame frame = tet_frame(mesh, cell);  // both ends lie in this cell
    for (int end = 0; end < 2; ++end) {  // 0: exit (t_in, nearer the eye), 1: far end (t_out)
      const double t = end == 0 ? x.t_in : x.t_out;
      Rgb g_t{}, g_s{};
      for (int c = 0; c < kChannels; ++c) {
        g_t[c] = end == 0 ? -g.length[j][c] : g.length[j][c];
        g_s[c] = end == 0 ? g.scalar_exit[j][c] : g.scalar_far[j][c];
      }
      const Vec3 p = trace.origin + t * trace.direction;
      const std::array<double, 4> lambda = barycentric(frame, p);
      // Scalars.
      if (on_cells) {
        sink.scalar(x.cell, g_s);
      } else {
        for (std::size_t k = 0; k < 4; ++k) {
          Rgb d{};
          for (int c = 0; c < kChannels; ++c) d[c] = g_s[c] * lambda[k];
          sink.scalar(tet[k], d);
        }
      }
      if (!positions) continue;
      // Positions: the face the end lies on (the smallest lambda), or none (the eye inside).
      // The two smallest |lambda|, the first index among equal ones (the order a stable sort
      // gives; an end on an edge has two equal zeros, and which face is used must not vary).
      // Selected by conditional moves, not branches (which face is random from end to end).
      std::array<double, 4> abs_lambda{};
      for (std::size_t k = 0; k < 4; ++k) abs_lambda[k] = std::fabs(lambda[k]);
      std::size_t m = 0;
      double abs_m = abs_lambda[0];
      for (std::size_t k = 1; k < 4; ++k) {
        const bool smaller = abs_lambda[k] < abs_m;
        m = smaller ? k : m;
        abs_m = smaller ? abs_lambda[k] : abs_m;
      }
      std::size_t second = m == 0 ? 1 : 0;
      double abs_second = abs_lambda[second];
      for (std::size_t k = second + 1; k < 4; ++k) {
        const bool smaller = k != m && abs_lambda[k] < abs_second;
        second = smaller ? k : second;
        abs_second = smaller ? abs_lambda[k] : abs_second;
      }
      if (abs_m > kOnFace) {  // interior point: t fixed, s(p) moves
        if (on_cells) continue;
        const Vec3& grad_s = traversal.gradient(cell);
        for (std::size_t k = 0; k < 4; ++k) {
          std::array<Rgb, 3> d{};
          for (int a = 0; a < 3; ++a)
            for (int c = 0; c < kChannels; ++c) d[a][c] = -g_s[c] * lambda[k] * grad_s[a];
          sink.position(tet[k], d);
        }
        continue;
      }
      if (abs_second <= kOnFace) ++on_edges;
      // m: the vertex opposite the face the end lies on.
      std::array<std::size_t, 3> f{};
      for (std::size_t k = 0, q = 0; k < 4; ++k)
        if (k != m) f[q++] = k;
      const Vec3& a = mesh.points[tet[f[0]]];
      const Vec3& b = mesh.points[tet[f[1]]];
      const Vec3& cpt = mesh.points[tet[f[2]]];
      Eigen::Matrix3d M;
      M.col(0) = trace.direction;
      M.col(1) = -(b - a);
      M.col(2) = -(cpt - a);
      double ds_du = 0.0, ds_dv = 0.0;
      if (!on_cells) {
        ds_du = mesh.scalars[tet[f[1]]] - mesh.scalars[tet[f[0]]];
        ds_dv = mesh.scalars[tet[f[2]]] - mesh.scalars[tet[f[0]]];
      }
      // M^T y = r for the three channels: the 3 x 3 cofactor inverse once; a (nearly) singular M
      // (the ray in or near the face's plane) the full-pivoting LU (well_conditioned,
      // mesh/gradients.hpp: threshold and measured agreement).
      std::array<Vec3, kChannels> y;
      if (well_conditioned(M.determinant(), M.col(0), M.col(1), M.col(2))) {
        const Eigen::Matrix3d inv = M.transpose().inverse();
        for (int c = 0; c < kChannels; ++c) y[c] = inv * Vec3(g_t[c], g_s[c] * ds_du, g_s[c] * ds_dv);
      } else {
        const Eigen::FullPivLU<Eigen::Matrix3d> lu(M.transpose());
        for (int c = 0; c < kChannels; ++c) y[c] = lu.solve(Vec3(g_t[c], g_s[c] * ds_du, g_s[c] * ds_dv));
      }
      // The face's barycentrics: the cell's, renormalised without the (~0) opposite one.
      const double sum = lambda[f[0]] + lambda[f[1]] + lambda[f[2]];
      for (std::size_t q = 0; q < 3; ++q) {
        const double w = lambda[f[q]] / sum;
        std::array<Rgb, 3> d{};
        for (int ax = 0; ax < 3; ++ax)
          for (int c = 0; c < kChannels; ++c) d[ax][c] = w * y[c][ax];
        sink.position(tet[f[q]], d);
      }
    }
  }
  return on_edges;
}

struct SparseSink {
  std::map<std::int32_t, Rgb> scalar_map;
  std::map<std::int32_t, std::array<Rgb, 3>> position_map;
  void scalar(std::int32_t i, const Rgb& d) {
    Rgb& e = scalar_map[i];
    for (int c = 0; c < kChannels; ++c) e[c] += d[c];
  }
  void position(std::int32_t i, const std::array<Rgb, 3>& d) {
    auto& e = position_map[i];
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < kChannels; ++c) e[a][c] += d[a][c];
  }
};

// Accumulates weight_c * contribution_c over channels into dense per-point arrays.
struct LossSink {
  Rgb weight{};
  std::vector<double>* d_scalar = nullptr;
  std::vector<std::array<double, 3>>* d_position = nullptr;
  // The sums are formed in locals before the stores: a store into the arrays could alias
  // `weight` for the compiler, which would reload it after each one.
  void scalar(std::int32_t i, const Rgb& d) {
    double s = 0.0;
    for (int c = 0; c < kChannels; ++c) s += weight[c] * d[c];
    (*d_scalar)[static_cast<std::size_t>(i)] += s;
  }
  void position(std::int32_t i, const std::array<Rgb, 3>& d) {
    const Rgb w = weight;
    std::array<double, 3> s{};
    for (std::size_t a = 0; a < 3; ++a)
      for (int c = 0; c < kChannels; ++c) s[a] += w[c] * d[a][c];
    std::array<double, 3>& e = (*d_position)[static_cast<std::size_t>(i)];
    for (std::size_t a = 0; a < 3; ++a) e[a] += s[a];
  }
};

}  // namespace

double PixelJacobian::channel_scale(int c) const {
  double s = 0.0;
  for (const Rgb& d : d_scalar) s = std::max(s, std::fabs(d[c]));
  for (const auto& d : d_position)
    for (const Rgb& e : d) s = std::max(s, std::fabs(e[c]));
  return s;
}

PixelJacobian pixel_jacobian(const TetTraversal& mesh, const TransferFunctions& tf, const ViewRay& view,
                             const Rgb& background) {
  RayTrace trace;
  mesh.trace(view, trace);
  const Ray ray = ray_from_trace(trace, background);
  // The chain below reads the segment blocks only.
  RayGradient g;
  exact_ray_gradient(tf, ray, g, GradientBlocks::segments);
  SparseSink sink;
  PixelJacobian out;
  out.intensity = g.intensity;
  out.undefined = g.undefined;
  out.cell_scalars = !mesh.mesh().cell_scalars.empty();
  out.ends_on_edges = chain_trace(mesh, trace, g, sink);
  for (const auto& [i, d] : sink.scalar_map) {
    out.index.push_back(i);
    out.d_scalar.push_back(d);
  }
  for (const auto& [i, d] : sink.position_map) {
    out.position_index.push_back(i);
    out.d_position.push_back(d);
  }
  return out;
}

LossGradient image_loss_gradient(const MeshCase& mc, const TetTraversal& mesh, const Image& target,
                                 unsigned threads, bool positions) {
  if (!mc.camera) throw std::invalid_argument(mc.source + ": camera: required for an image loss");
  if (mc.shading.enabled)
    throw std::invalid_argument(mc.source + ": shading: a shaded render is not differentiated");
  const Camera& cam = *mc.camera;
  if (target.width != cam.width || target.height != cam.height)
    throw std::invalid_argument("target image is " + std::to_string(target.width) + " x " +
                                std::to_string(target.height) + ", the camera renders " +
                                std::to_string(cam.width) + " x " + std::to_string(cam.height));
  const TetMesh& m = mesh.mesh();
  LossGradient out;
  out.cell_scalars = !m.cell_scalars.empty();
  out.image = Image(cam.width, cam.height);
  const std::size_t n_scalar = out.cell_scalars ? m.tets.size() : m.points.size();
  const unsigned workers = parallel_workers(cam.height, threads);
  struct Part {
    std::vector<double> d_scalar;
    std::vector<std::array<double, 3>> d_position;
    double loss = 0.0;
    long on_edges = 0, failed = 0;
    RayTrace trace;
    Ray ray;
    RayGradient grad;
  };
  std::vector<Part> parts(workers);
  const ExactRayGradient gradient(mc.transfer);  // prepared once for every pixel
  for (Part& p : parts) {
    p.d_scalar.assign(n_scalar, 0.0);
    if (positions) p.d_position.assign(m.points.size(), {0.0, 0.0, 0.0});
  }
  const CameraRays camera_rays(cam);  // the camera's frame once per render, the rays cam's bits
  parallel_for_striped(cam.height, threads, [&](long long row, unsigned id) {
    Part& p = parts[id];
    const int y = static_cast<int>(row);
    for (int x = 0; x < cam.width; ++x) {
      mesh.trace(camera_rays.ray_for_pixel(x, y), p.trace);
      ray_from_trace(p.trace, mc.background, p.ray);
      gradient(p.ray, p.grad, GradientBlocks::segments);
      out.image.at(x, y) = p.grad.intensity;
      LossSink sink;
      bool finite = true;
      for (int c = 0; c < kChannels; ++c) {
        const double r = p.grad.intensity[c] - target.at(x, y)[c];
        sink.weight[c] = 2.0 * r;
        p.loss += r * r;
        finite = finite && std::isfinite(r);
      }
      finite = finite && p.grad.all_finite();  // what a finite channel_scale of every channel says
      if (!finite || !p.grad.undefined.empty()) {  // undefined: a derivative does not exist (a jump)
        ++p.failed;
        continue;
      }
      sink.d_scalar = &p.d_scalar;
      sink.d_position = &p.d_position;
      p.on_edges += chain_trace(mesh, p.trace, p.grad, sink, positions);
    }
  });
  out.d_scalar.assign(n_scalar, 0.0);
  if (positions) out.d_position.assign(m.points.size(), {0.0, 0.0, 0.0});
  // Summed in worker order; each worker took fixed rows (parallel_for_striped): the same sums,
  // bit for bit, on every run with the same thread count.
  for (const Part& p : parts) {
    for (std::size_t i = 0; i < n_scalar; ++i) out.d_scalar[i] += p.d_scalar[i];
    for (std::size_t i = 0; i < out.d_position.size(); ++i)
      for (std::size_t a = 0; a < 3; ++a) out.d_position[i][a] += p.d_position[i][a];
    out.loss += p.loss;
    out.ends_on_edges += p.on_edges;
    out.pixels_failed += p.failed;
  }
  return out;
}

}  // namespace rayint
