#include "rayint/special/special_functions.hpp"

// Real-argument functions of libcerf 1.3 (cerf.h), declared here because cerf.h itself pulls in
// C99 complex types that ISO C++ rejects.
extern "C" {
double erfcx(double x);
double dawson(double x);
double erfi(double x);
}

namespace rayint::special {

double erfcx(double x) { return ::erfcx(x); }
double dawson(double x) { return ::dawson(x); }
double erfi(double x) { return ::erfi(x); }

}  // namespace rayint::special
