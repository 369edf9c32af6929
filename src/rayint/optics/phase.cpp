#include "rayint/optics/phase.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "rayint/core/math.hpp"

namespace rayint {

namespace {
constexpr double kInv4Pi = 1.0 / (4.0 * kPi);

// Lambert-sphere CDF in theta and its derivative (the density in theta).
double lambert_cdf(double theta) {
  return 4.0 / (3.0 * kPi) *
         (0.5 * theta + 0.25 * theta * std::cos(2 * theta) - 0.375 * std::sin(2 * theta));
}
double lambert_density_theta(double theta) {
  const double s = std::sin(theta);
  return 4.0 / (3.0 * kPi) * (s * s - theta * s * std::cos(theta));
}
}  // namespace

PhaseFunction PhaseFunction::isotropic() { return PhaseFunction(Kind::isotropic, 0.0); }

PhaseFunction PhaseFunction::henyey_greenstein(double g) {
  if (!(std::abs(g) < 1.0)) throw std::invalid_argument("Henyey-Greenstein g must satisfy |g| < 1");
  return PhaseFunction(Kind::henyey_greenstein, g);
}

PhaseFunction PhaseFunction::lambert_sphere() { return PhaseFunction(Kind::lambert_sphere, 0.0); }

const char* PhaseFunction::name() const {
  switch (kind_) {
    case Kind::isotropic: return "isotropic";
    case Kind::henyey_greenstein: return "henyey_greenstein";
    case Kind::lambert_sphere: return "lambert_sphere";
  }
  return "?";
}

double PhaseFunction::eval(double cos_theta) const {
  cos_theta = std::clamp(cos_theta, -1.0, 1.0);
  switch (kind_) {
    case Kind::isotropic: return kInv4Pi;
    case Kind::henyey_greenstein: {
      const double denom = 1.0 + g_ * g_ - 2.0 * g_ * cos_theta;
      return kInv4Pi * (1.0 - g_ * g_) / (denom * std::sqrt(denom));
    }
    case Kind::lambert_sphere: {
      const double theta = std::acos(cos_theta);
      const double phi = 8.0 / (3.0 * kPi) * (std::sin(theta) - theta * cos_theta);
      return kInv4Pi * phi;
    }
  }
  return 0.0;
}

double PhaseFunction::mean_cosine() const {
  switch (kind_) {
    case Kind::isotropic: return 0.0;
    case Kind::henyey_greenstein: return g_;
    case Kind::lambert_sphere: return -4.0 / 9.0;
  }
  return 0.0;
}

double PhaseFunction::sample_cos_theta(double u) const {
  u = std::clamp(u, 0.0, 1.0);
  switch (kind_) {
    case Kind::isotropic: return 1.0 - 2.0 * u;
    case Kind::henyey_greenstein: {
      if (std::abs(g_) < 1e-4) return 1.0 - 2.0 * u;  // HG differs from isotropic by O(g) here
      const double s = (1.0 - g_ * g_) / (1.0 - g_ + 2.0 * g_ * u);
      return std::clamp((1.0 + g_ * g_ - s * s) / (2.0 * g_), -1.0, 1.0);
    }
    case Kind::lambert_sphere: {
      // Safeguarded Newton on F(theta) = u over [0, pi]; F is increasing.
      double lo = 0.0, hi = kPi, theta = kPi * u;
      for (int it = 0; it < 100; ++it) {
        const double f = lambert_cdf(theta) - u;
        if (f > 0) hi = theta; else lo = theta;
        const double d = lambert_density_theta(theta);
        double next = d > 0 ? theta - f / d : 0.5 * (lo + hi);
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        if (std::abs(next - theta) < 1e-14) { theta = next; break; }
        theta = next;
      }
      return std::cos(theta);
    }
  }
  return 1.0;
}

void orthonormal_basis(const Vec3& n, Vec3& t, Vec3& b) {
  const double sign = std::copysign(1.0, n.z());
  const double a = -1.0 / (sign + n.z());
  const double c = n.x() * n.y() * a;
  t = Vec3(1.0 + sign * n.x() * n.x() * a, sign * c, -sign * n.x());
  b = Vec3(c, sign + n.y() * n.y() * a, -n.y());
}

Vec3 PhaseFunction::sample(const Vec3& w_in, double u1, double u2) const {
  const double mu = sample_cos_theta(u1);
  const double sin_theta = std::sqrt(std::max(0.0, 1.0 - mu * mu));
  const double phi = 2.0 * kPi * u2;
  Vec3 t, b;
  orthonormal_basis(w_in, t, b);
  return (mu * w_in + sin_theta * (std::cos(phi) * t + std::sin(phi) * b)).normalized();
}

}  // namespace rayint
