#pragma once
// Special functions used by the closed forms, all from well-kept libraries:
//   erfcx(x) = exp(x^2) erfc(x)              libcerf (S. G. Johnson's Faddeeva package)
//   dawson(x) = exp(-x^2) int_0^x exp(t^2)    libcerf
//   erfi(x) = -i erf(i x), real x             libcerf (only the paper's literal formula uses it)
// libcerf's header declares complex functions with C99 `double _Complex`, which is not ISO C++;
// we declare only the real-argument functions we call, with the same signatures.
namespace rayint::special {

double erfcx(double x);
double dawson(double x);
double erfi(double x);

}  // namespace rayint::special
