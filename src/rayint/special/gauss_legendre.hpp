#pragma once
// Gauss-Legendre quadrature on [0, 1] (scattering/ uses it as the half-range "double-Gauss"
// rule of discrete ordinates, Sykes 1951): nodes are the roots of P_n mapped to [0, 1], found by
// Newton's method from Tricomi's initial guess to |dx| < 1e-15; weights 1/((1 - x^2) P_n'(x)^2).
// Exact for polynomials of degree 2n - 1 (tested up to n = 128 with x^(2n-1)).
#include <vector>

namespace rayint {

struct GaussLegendre {
  std::vector<double> nodes;    // ascending, in (0, 1)
  std::vector<double> weights;  // summing to 1
};

GaussLegendre gauss_legendre_01(int n);

}  // namespace rayint
