// paper.cpp -- the literal closed form of Williams & Max (1992), Sec. 3.3.
//   q2 != 0: (q2 q4 - q1 q5 + q2 q5 t_{i+1})/q2^2
//            - (q2 q4 - q1 q5 + q2 q5 t_i)/q2^2 * e^{(t_i - t_{i+1})(2 q1 + q2 t_i + q2 t_{i+1})/2}
//            + sqrt(pi/2) (q2^2 q3 - q1 q2 q4 + q1^2 q5 - q2 q5) / (q2^{2.5} e^{(q1+q2 t_{i+1})^2/(2 q2)})
//              * (Erfi((q1 + q2 t_{i+1})/sqrt(2 q2)) - Erfi((q1 + q2 t_i)/sqrt(2 q2)))
//   q2 == 0: [(q1^2 q3 - q1 q4 + 2 q5 + q1^2 q4 t + ... )/q1^3] at t_{i+1} minus at t_i times e^{q1(t_i - t_{i+1})}
// Evaluated in std::complex<double> so that sqrt(2 q2) and q2^{2.5} are imaginary for q2 < 0 as
// in the paper; Erfi of a real argument is libcerf's erfi, of an imaginary one i*erf (the
// paper's own definition). No rescaling, no series: this method exists to show the printed
// formula's overflow (e^{x^2} growth) and cancellation; it is not used for anything else.
#include "rayint/integrators/paper.hpp"

#include <cmath>
#include <complex>

#include "rayint/core/math.hpp"
#include "rayint/model/pieces.hpp"
#include "rayint/special/special_functions.hpp"

namespace rayint {
namespace {

using Complex = std::complex<double>;

// Erfi for an argument that is either real or pure imaginary (paper, Sec. 3.3).
Complex erfi_paper(Complex x) {
  if (x.imag() == 0.0) return {special::erfi(x.real()), 0.0};
  return {0.0, std::erf(x.imag())};  // Erfi(i b) = i (2/sqrt(pi)) int_0^b e^{-u^2} du
}

// Linear coefficients y = c0 + c1 s through (s0, y0), (s1, y1); c1 = 0 when s0 == s1.
void line_through(double s0, double y0, double s1, double y1, double& c0, double& c1) {
  c1 = (s1 == s0) ? 0.0 : (y1 - y0) / (s1 - s0);
  c0 = y0 - c1 * s0;
}

}  // namespace

double paper_emission(const PaperInterval& iv) {
  const double q1 = iv.q1, q2 = iv.q2, q3 = iv.q3, q4 = iv.q4, q5 = iv.q5;
  const double ti = iv.t_begin, tn = iv.t_end;
  if (q2 == 0.0) {
    auto bracket = [&](double t) {
      return q1 * q1 * q3 - q1 * q4 + 2 * q5 + q1 * q1 * q4 * t - 2 * q1 * q5 * t +
             q1 * q1 * q5 * t * t;
    };
    return bracket(tn) / (q1 * q1 * q1) -
           bracket(ti) * std::exp(q1 * (ti - tn)) / (q1 * q1 * q1);
  }
  const Complex cq2(q2, 0.0);
  const Complex root = std::sqrt(2.0 * cq2);
  const double first = (q2 * q4 - q1 * q5 + q2 * q5 * tn) / (q2 * q2);
  const double second = (q2 * q4 - q1 * q5 + q2 * q5 * ti) / (q2 * q2) *
                        std::exp((ti - tn) * (2 * q1 + q2 * ti + q2 * tn) / 2);
  const Complex prefactor = std::sqrt(kPi / 2) *
                            (q2 * q2 * q3 - q1 * q2 * q4 + q1 * q1 * q5 - q2 * q5) /
                            (std::pow(cq2, 2.5) *
                             std::exp(Complex((q1 + q2 * tn) * (q1 + q2 * tn) / (2 * q2), 0.0)));
  const Complex erfi_difference =
      erfi_paper((q1 + q2 * tn) / root) - erfi_paper((q1 + q2 * ti) / root);
  return (first - second + prefactor * erfi_difference).real();
}

double paper_transmittance(const PaperInterval& iv) {
  const double q1 = iv.q1, q2 = iv.q2, ti = iv.t_begin, tn = iv.t_end;
  return std::exp(-(q1 * tn + q2 * tn * tn / 2 - q1 * ti - q2 * ti * ti / 2));
}

RayResult PaperIntegrator::integrate_segments(const Ray& ray, Diagnostics* diag) const {
  RayResult r = RayResult::of_background(ray.background);
  for (const auto& seg : ray.segments) {
    const std::vector<Piece>& pieces = splitter_.pieces(seg);
    // Eq. 13: S(t) = v + w t, t measured from where the ray enters the cell (segment).
    const double v = seg.scalar_far;
    const double w = (seg.scalar_exit - seg.scalar_far) / seg.length;
    double t_flat = 0.0;  // for w == 0 the single piece spans [0, L]
    for (const auto& piece : pieces) {
      const double ti = (w == 0.0) ? t_flat : (piece.scalar_far - v) / w;
      const double tn = (w == 0.0) ? t_flat + piece.length : (piece.scalar_exit - v) / w;
      t_flat = tn;
      for (int c = 0; c < kChannels; ++c) {
        // Transfer-function interval: rho = a + b s, kappa = kc + kd s, kappa rho = f + g s + h s^2.
        double a, b, kc, kd;
        line_through(piece.scalar_far, piece.rho_far[c], piece.scalar_exit, piece.rho_exit[c], a, b);
        line_through(piece.scalar_far, piece.kappa_far[c], piece.scalar_exit, piece.kappa_exit[c],
                     kc, kd);
        const double f = kc * a, g = kc * b + kd * a, h = kd * b;
        const PaperInterval iv{a + b * v,          b * w,
                               f + g * v + h * v * v, g * w + 2 * h * v * w,
                               h * w * w,          ti,
                               tn};
        const double em = paper_emission(iv);
        const double tr = paper_transmittance(iv);
        r.intensity[c] = r.intensity[c] * tr + em;
        r.transmittance[c] *= tr;
        if (diag) {
          diag->count(iv.q2 == 0.0 ? "q2_zero" : (iv.q2 > 0.0 ? "erfi_real" : "erfi_imaginary"));
          if (!std::isfinite(em)) diag->count("non_finite");
        }
      }
    }
  }
  return r;
}

}  // namespace rayint
