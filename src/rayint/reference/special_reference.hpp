#pragma once
// erfcx and Dawson's integral in 50-digit arithmetic (cpp_bin_float_50), the independent reference
// for the vector approximations of special/erfcx_simd-inl.hpp (their coefficient generator
// tools/gen_special_simd_tables.cpp and tests/test_special_simd.cpp). See special_reference.cpp.
#include "rayint/reference/reference.hpp"
#include "rayint/reference/reference_detail.hpp"

namespace rayint {

// x >= 0; hi is the correctly rounded double, hi + lo carries ~50 digits.
ExtendedValue erfcx_reference(double x);   // exp(x^2) erfc(x)
ExtendedValue dawson_reference(double x);  // exp(-x^2) int_0^x exp(t^2) dt

namespace reference_detail {
Real erfcx_real(const Real& x);   // x >= 0
Real dawson_real(const Real& x);  // x >= 0
}  // namespace reference_detail

}  // namespace rayint
