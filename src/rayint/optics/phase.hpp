#pragma once
// Phase functions of Max (1995, Sec. 5): the fraction of light scattered from one direction into
// another, per steradian, normalized so that it integrates to 1 over the sphere.
//
// Convention: cos_theta = dot(w_in, w_out), where both are directions of *propagation* (w_in is
// where the light was going before it scattered). theta = 0 is forward scattering.
//
// - isotropic: p = 1/(4 pi).
// - Henyey-Greenstein (1941): p = (1 - g^2) / (4 pi (1 + g^2 - 2 g cos_theta)^(3/2)), mean cosine g,
//   |g| < 1; sampled by the closed-form inverse CDF.
// - Lambert sphere (Blinn 1982; Max 1995 Eq. 18): a medium of large diffuse spheres,
//   Phi(alpha) = 8/(3 pi) (sin alpha + (pi - alpha) cos alpha) with phase angle alpha = pi - theta,
//   averaging to 1 over the sphere, so p = Phi / (4 pi). It scatters backward: mean cosine -4/9.
//   Sampled by inverting its CDF in theta, F = 4/(3 pi) (theta/2 + theta cos(2 theta)/4
//   - 3 sin(2 theta)/8), by safeguarded Newton iteration to 1e-14 in theta.
// Normalization and mean cosine are checked by quadrature in tests/test_phase.cpp.
#include "rayint/geometry/vec3.hpp"

namespace rayint {

class PhaseFunction {
 public:
  enum class Kind { isotropic, henyey_greenstein, lambert_sphere };

  static PhaseFunction isotropic();
  static PhaseFunction henyey_greenstein(double g);  // throws std::invalid_argument if |g| >= 1
  static PhaseFunction lambert_sphere();

  Kind kind() const { return kind_; }
  double g() const { return g_; }  // the HG parameter (0 for the others)
  const char* name() const;

  double eval(double cos_theta) const;  // per steradian
  double mean_cosine() const;           // integral of p * cos_theta over the sphere
  double sample_cos_theta(double u) const;  // u uniform in [0, 1)
  // An outgoing propagation direction for incoming `w_in` (unit), from two uniforms in [0, 1);
  // its density over the sphere is eval(dot(w_in, w_out)).
  Vec3 sample(const Vec3& w_in, double u1, double u2) const;

 private:
  PhaseFunction(Kind kind, double g) : kind_(kind), g_(g) {}
  Kind kind_;
  double g_;
};

// An orthonormal basis (t, b) completing the unit vector n (Duff et al. 2017).
void orthonormal_basis(const Vec3& n, Vec3& t, Vec3& b);

}  // namespace rayint
