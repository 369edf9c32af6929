// Cube-face direction bins and bin-averaged phase matrices; see direction_bins.hpp.
#include "rayint/scattering/direction_bins.hpp"

#include <cmath>
#include <stdexcept>

namespace rayint {

namespace {

double corner(double x, double y) { return std::atan(x * y / std::sqrt(1 + x * x + y * y)); }

double rect_solid_angle(double x1, double x2, double y1, double y2) {
  return corner(x2, y2) - corner(x1, y2) - corner(x2, y1) + corner(x1, y1);
}

// Point (u, v) on face f of the cube [-1, 1]^3, as a direction (not normalized).
Vec3 face_point(int f, double u, double v) {
  switch (f) {
    case 0: return Vec3(1, u, v);
    case 1: return Vec3(-1, v, u);
    case 2: return Vec3(v, 1, u);
    case 3: return Vec3(u, -1, v);
    case 4: return Vec3(u, v, 1);
    default: return Vec3(v, u, -1);
  }
}

}  // namespace

std::vector<DirectionBin> cube_face_bins(int n, int s) {
  if (n < 1 || s < 1) throw std::invalid_argument("direction bins: n and sub must be >= 1");
  std::vector<DirectionBin> bins;
  const double h = 2.0 / n, hs = h / s;
  for (int f = 0; f < 6; ++f)
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        DirectionBin b;
        const double u0 = -1 + i * h, v0 = -1 + j * h;
        b.center = face_point(f, u0 + h / 2, v0 + h / 2).normalized();
        b.solid_angle = rect_solid_angle(u0, u0 + h, v0, v0 + h);
        for (int a = 0; a < s; ++a)
          for (int c = 0; c < s; ++c) {
            const double u = u0 + a * hs, v = v0 + c * hs;
            b.sub_directions.push_back(face_point(f, u + hs / 2, v + hs / 2).normalized());
            b.sub_solid_angles.push_back(rect_solid_angle(u, u + hs, v, v + hs));
          }
        bins.push_back(std::move(b));
      }
  return bins;
}

std::vector<double> bin_phase_matrix(const std::vector<DirectionBin>& bins, const PhaseFunction& p) {
  const std::size_t m = bins.size();
  std::vector<double> P(m * m, 0.0);
  for (std::size_t a = 0; a < m; ++a) {
    double row = 0;
    for (std::size_t b = 0; b < m; ++b) {
      double sum = 0;
      for (std::size_t i = 0; i < bins[a].sub_directions.size(); ++i)
        for (std::size_t j = 0; j < bins[b].sub_directions.size(); ++j)
          sum += bins[a].sub_solid_angles[i] * bins[b].sub_solid_angles[j] *
                 p.eval(bins[a].sub_directions[i].dot(bins[b].sub_directions[j]));
      P[a * m + b] = sum / bins[a].solid_angle;
      row += P[a * m + b];
    }
    for (std::size_t b = 0; b < m; ++b) P[a * m + b] /= row;
  }
  return P;
}

std::vector<double> bin_phase_from(const std::vector<DirectionBin>& bins, const PhaseFunction& p,
                                   const Vec3& w_in) {
  std::vector<double> f(bins.size(), 0.0);
  double total = 0;
  for (std::size_t b = 0; b < bins.size(); ++b) {
    for (std::size_t j = 0; j < bins[b].sub_directions.size(); ++j)
      f[b] += bins[b].sub_solid_angles[j] * p.eval(w_in.dot(bins[b].sub_directions[j]));
    total += f[b];
  }
  for (double& x : f) x /= total;
  return f;
}

}  // namespace rayint
