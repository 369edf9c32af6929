#pragma once
// Polynomials in one variable as coefficient vectors (p(x) = sum_k c[k] x^k), for scalars along
// rays through higher-order cells (model/poly_ray.hpp): evaluation, derivative, antiderivative,
// re-expansion about another point, and the real roots in an interval. Templates, so that the
// double-precision methods (cells/) and the 50-digit reference (reference/poly_reference.cpp,
// with cpp_bin_float_50) run the same algorithm at their own precision.
//
// Roots in [a, b] (real_roots): recursive on the derivative. The critical points (the roots of
// p' in (a, b), found the same way) cut [a, b] into intervals on which p is monotone; each of
// them holds at most one root, bracketed by a sign change of p at its ends and found by
// TOMS 748 (Alefeld, Potra and Shi 1995; boost::math::tools::toms748_solve) to the full
// precision of T, or sits exactly at an end where p is 0. Degree <= 1 is solved directly.
// Tangential (double) roots: a root of even multiplicity is a critical point; it is reported
// when p is exactly 0 there, and otherwise, depending on the rounding of p at the critical point,
// as nothing (p stays on one side) or as two roots that close in on the critical point from
// either side. Callers that split at roots (crossings) also split at the critical points
// (split_points), so both outcomes give pieces on which p is monotone and lies between two
// consecutive levels up to rounding: a touch without a sign change has no kink to split.
// Accuracy: each simple root to a few ulps of T times its condition number |p / (x p')|
// (toms748 stops when the bracket is within 2 ulps; tests [cells] check against polynomials
// built from known roots).
#include <algorithm>
#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

namespace rayint::poly {

template <class T>
T eval(const std::vector<T>& c, const T& x) {
  T f = 0;
  for (std::size_t k = c.size(); k-- > 0;) f = f * x + c[k];
  return f;
}

template <class T>
std::vector<T> derivative(const std::vector<T>& c) {
  std::vector<T> d;
  for (std::size_t k = 1; k < c.size(); ++k) d.push_back(c[k] * T(static_cast<int>(k)));
  return d;
}

// The antiderivative that is 0 at x = 0.
template <class T>
std::vector<T> antiderivative(const std::vector<T>& c) {
  std::vector<T> a(c.size() + 1, T(0));
  for (std::size_t k = 0; k < c.size(); ++k) a[k + 1] = c[k] / T(static_cast<int>(k + 1));
  return a;
}

// q(u) = p(x0 + sign * u) (sign = +1 or -1): the Taylor coefficients of p at x0, signed.
template <class T>
std::vector<T> shifted(std::vector<T> c, const T& x0, int sign) {
  // Repeated synthetic division by (x - x0) (Horner's scheme for all derivatives).
  const std::size_t n = c.size();
  for (std::size_t i = 0; i + 1 < n; ++i)
    for (std::size_t k = n - 1; k-- > i;) c[k] += x0 * c[k + 1];
  if (sign < 0)
    for (std::size_t k = 1; k < n; k += 2) c[k] = -c[k];
  return c;
}

template <class T>
int degree(const std::vector<T>& c) {  // of the trimmed polynomial; -1 for the zero polynomial
  for (std::size_t k = c.size(); k-- > 0;)
    if (c[k] != 0) return static_cast<int>(k);
  return -1;
}

namespace detail {
template <class T>
int sign_of(const T& x) {
  return x > 0 ? 1 : (x < 0 ? -1 : 0);
}

// The root of the monotone p in (x0, x1), where p(x0) and p(x1) have opposite signs.
template <class T>
T bracketed_root(const std::vector<T>& c, T x0, T x1, T f0, T f1) {
  std::uintmax_t max_iter = 200;
  const auto f = [&c](const T& x) { return eval(c, x); };
  const auto r = boost::math::tools::toms748_solve(
      f, x0, x1, f0, f1, boost::math::tools::eps_tolerance<T>(std::numeric_limits<T>::digits - 1),
      max_iter);
  if (max_iter >= 200) throw std::runtime_error("poly::real_roots: TOMS 748 did not converge");
  // The midpoint of the final bracket, or its end where p is exactly 0.
  if (eval(c, r.first) == 0) return r.first;
  if (eval(c, r.second) == 0) return r.second;
  return (r.first + r.second) / 2;
}
}  // namespace detail

// The distinct real roots of p in [a, b] (a < b), sorted. The zero polynomial has no isolated
// roots: returns none.
template <class T>
std::vector<T> real_roots(const std::vector<T>& c, const T& a, const T& b) {
  std::vector<T> roots;
  const int n = degree(c);
  if (n <= 0) return roots;
  if (n == 1) {
    const T x = -c[0] / c[1];
    if (x >= a && x <= b) roots.push_back(x);
    return roots;
  }
  std::vector<T> knots{a};
  for (const T& x : real_roots(derivative(c), a, b))
    if (x > a && x < b) knots.push_back(x);
  knots.push_back(b);
  std::vector<T> values;
  for (const T& x : knots) values.push_back(eval(c, x));
  for (std::size_t i = 0; i < knots.size(); ++i) {
    if (values[i] == 0) roots.push_back(knots[i]);
    if (i + 1 < knots.size() && detail::sign_of(values[i]) * detail::sign_of(values[i + 1]) < 0)
      roots.push_back(detail::bracketed_root(c, knots[i], knots[i + 1], values[i], values[i + 1]));
  }
  std::sort(roots.begin(), roots.end());
  roots.erase(std::unique(roots.begin(), roots.end()), roots.end());
  return roots;
}

// Where a piece of the ray must end on [0, length] so that on each piece p is monotone and
// between two consecutive `levels` (sorted, e.g. transfer-function breakpoints): 0, the
// critical points of p, every crossing of a level, and length; sorted, distinct.
template <class T>
std::vector<T> split_points(const std::vector<T>& c, const std::vector<T>& levels,
                            const T& length) {
  std::vector<T> knots{T(0)};
  for (const T& x : real_roots(derivative(c), T(0), length))
    if (x > 0 && x < length) knots.push_back(x);
  knots.push_back(length);
  std::vector<T> out = knots;
  std::vector<T> shifted_c = c;
  for (std::size_t i = 0; i + 1 < knots.size(); ++i) {
    const T f0 = eval(c, knots[i]), f1 = eval(c, knots[i + 1]);
    const T lo = std::min(f0, f1), hi = std::max(f0, f1);
    for (const T& level : levels) {
      if (!(level > lo && level < hi)) continue;  // no sign change of p - level inside
      shifted_c[0] = c[0] - level;
      out.push_back(detail::bracketed_root(shifted_c, knots[i], knots[i + 1], f0 - level, f1 - level));
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace rayint::poly
