#pragma once
// Array forms of the vector special functions, dispatched at run time to the best Highway target
// of this CPU (SSE4, AVX2, AVX-512, ...): for tests, benchmarks and accuracy reports. The kernels
// themselves live in erfcx_simd-inl.hpp (erfcx, Dawson) and Highway's hwy/contrib/math (Exp,
// Expm1); exact_batch inlines them. Accuracy is stated in erfcx_simd-inl.hpp.
#include <cstddef>

namespace rayint::special {

// y[i] = f(x[i]) for i < n; x >= 0 for erfcx and Dawson. x and y may alias.
void erfcx_array(const double* x, double* y, std::size_t n);
void dawson_array(const double* x, double* y, std::size_t n);
void exp_array(const double* x, double* y, std::size_t n);    // Highway Exp, documented 1 ulp
void expm1_array(const double* x, double* y, std::size_t n);  // Highway Expm1, documented 4 ulp
// y[i] = exp(-x[i]): table-driven in vectors for 0 <= x <= 700 (at most ~0.52 ulp; 0.516
// measured against 50 digits, std::exp's class), std::exp elsewhere (erfcx_simd.cpp). x and y
// must not alias.
void exp_neg_array(const double* x, double* y, std::size_t n);

// Name of the Highway target the dispatch picked on this CPU ("AVX3", "AVX2", "SSE4", ...).
const char* simd_target_name();

}  // namespace rayint::special
