// Derivative of psi_table's piece optics; the branches are psi_table.cpp's (see the header).
#include "rayint/integrators/psi_table_grad.hpp"

#include <algorithm>
#include <cmath>

#include "rayint/integrators/exact.hpp"
#include "rayint/integrators/exact_grad.hpp"
#include "rayint/integrators/ray_gradient_chain.hpp"

namespace rayint {
namespace {

PieceOpticsGrad psi_piece_grad(const PsiTable& table, table::Lookup lookup, const ChannelPiece& p) {
  PieceOpticsGrad g;  // transmittance 1, emission 0, derivatives 0
  const double x_exit = p.rho_exit * p.length;
  const double x_far = p.rho_far * p.length;
  const double T = 0.5 * (x_exit + x_far);
  if (!(T > 0.0)) return g;  // psi_table: transparent, skipped
  const PsiTable::ValueGrad v = table.lookup_grad(x_exit, x_far, lookup);
  const double zeta = std::exp(-T);
  const double dzeta = -0.5 * zeta;  // d zeta / d x_exit = d zeta / d x_far
  double w_exit, w_far, dw_exit_dxe, dw_exit_dxf, dw_far_dxe, dw_far_dxf;
  if (T <= kThinDepth) {
    const double alpha = -std::expm1(-T);
    const double dalpha = 0.5 * zeta;
    w_exit = std::clamp(v.value.one_minus_psi, 0.0, alpha);
    if (v.value.one_minus_psi < 0.0) {
      dw_exit_dxe = dw_exit_dxf = 0.0;
    } else if (v.value.one_minus_psi > alpha) {
      dw_exit_dxe = dw_exit_dxf = dalpha;
    } else {
      dw_exit_dxe = v.domp_dexit;
      dw_exit_dxf = v.domp_dfar;
    }
    w_far = alpha - w_exit;
    dw_far_dxe = dalpha - dw_exit_dxe;
    dw_far_dxf = dalpha - dw_exit_dxf;
  } else {
    const double psi = std::clamp(v.value.psi, zeta, 1.0);
    double dpsi_dxe, dpsi_dxf;
    if (v.value.psi < zeta) {
      dpsi_dxe = dpsi_dxf = dzeta;
    } else if (v.value.psi > 1.0) {
      dpsi_dxe = dpsi_dxf = 0.0;
    } else {
      dpsi_dxe = v.dpsi_dexit;
      dpsi_dxf = v.dpsi_dfar;
    }
    w_exit = 1.0 - psi;
    w_far = psi - zeta;
    dw_exit_dxe = -dpsi_dxe;
    dw_exit_dxf = -dpsi_dxf;
    dw_far_dxe = dpsi_dxe - dzeta;
    dw_far_dxf = dpsi_dxf - dzeta;
  }
  g.optics.transmittance = zeta;
  g.optics.weight_exit = w_exit;
  g.optics.weight_far = w_far;
  g.optics.emission = p.kappa_exit * w_exit + p.kappa_far * w_far;
  const double de_dxe = p.kappa_exit * dw_exit_dxe + p.kappa_far * dw_far_dxe;
  const double de_dxf = p.kappa_exit * dw_exit_dxf + p.kappa_far * dw_far_dxf;
  g.de_kappa_exit = w_exit;
  g.de_kappa_far = w_far;
  g.de_rho_exit = p.length * de_dxe;
  g.de_rho_far = p.length * de_dxf;
  g.de_length = p.rho_exit * de_dxe + p.rho_far * de_dxf;
  g.dt_rho_exit = g.dt_rho_far = dzeta * p.length;
  g.dt_length = dzeta * (p.rho_exit + p.rho_far);
  return g;
}

}  // namespace

RayGradient psi_table_ray_gradient(const TransferFunctions& tf, const Ray& ray, int size, table::Lookup lookup) {
  const std::shared_ptr<const PsiTable> table = PsiTable::shared(size, lookup);
  RayGradient grad;
  auto source = detail::each_piece_channel([&](const ChannelPiece& cp, const PieceOpticsGrad*) {
    return psi_piece_grad(*table, lookup, cp);
  });
  detail::chain_ray_gradient(tf, ray, grad, source, detail::PieceEnds::moving);
  return grad;
}

}  // namespace rayint
