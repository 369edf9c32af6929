#pragma once
// One shared set of error measures against a reference known beyond double precision
// (hi + lo). They handle 0, NaN and Inf: a non-finite value has infinite error; a zero
// reference gives relative error 0 for an exact zero and +inf otherwise.
#include <cmath>
#include <limits>

#include "rayint/core/statistics.hpp"  // kUnderflowFloor
#include "rayint/reference/reference.hpp"

namespace rayint {

// |x - (hi + lo)|, evaluated so that it is accurate even below one ulp of hi.
double absolute_error(double x, const ExtendedValue& ref);
double relative_error(double x, const ExtendedValue& ref);
// Error in units of the spacing of doubles at the reference value (ulp(0) = denorm_min).
double ulp_error(double x, const ExtendedValue& ref);
// Spacing of doubles at |x|.
double ulp_of(double x);

// Relative error of a plain double against a plain double (for tests of limits etc.).
double relative_error(double x, double ref);

// Scoring with the underflow floor (core/statistics.hpp kUnderflowFloor), the one definition
// stress, gate and sweep use. A reference below the floor in magnitude has underflowed:
bool underflowed(const ExtendedValue& ref);  // |ref.hi| < kUnderflowFloor
// |x - ref| / max(|ref|, kUnderflowFloor): the relative error where the reference has not
// underflowed, else the absolute error in units of the floor; +inf for non-finite x.
double scored_error(double x, const ExtendedValue& ref);

}  // namespace rayint
