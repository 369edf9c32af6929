// Integrates one piece with the installed library and checks it against Eq. 6.
#include <cmath>
#include <cstdio>

#include "rayint/integrators/exact.hpp"

int main() {
  rayint::ChannelPiece p{2.0, 0.5, 0.5, 3.0, 3.0};  // L, rho_far, rho_exit, kappa_far, kappa_exit
  const double expected = 3.0 * -std::expm1(-1.0);
  const double got = rayint::exact_piece(p).emission;
  std::printf("emission %.17g expected %.17g\n", got, expected);
  return std::fabs(got - expected) <= 1e-15 * expected ? 0 : 1;
}
