// VTK 9.1's transfer-function curves (vtkPiecewiseFunction, vtkColorTransferFunction) and
// vtkMath's colour conversions; formulas and sources in the header. Accuracy: agrees with VTK 9.1
// (python3-vtk9) to 1e-12 on the preset fixtures (tests "[tf]"), which is rounding.
#include "rayint/model/vtk_transfer_function.hpp"

#include <algorithm>
#include <cmath>

#include "rayint/core/math.hpp"

namespace rayint {
namespace {

// VTK moves the midpoint away from the ends "to avoid degenerate math".
double clamp_midpoint(double m) { return std::clamp(m, 0.00001, 0.99999); }

// s -> s' (the midpoint's linear readjustment).
double midpoint_adjusted(double s, double m) {
  return s < m ? 0.5 * s / m : 0.5 + 0.5 * (s - m) / (1.0 - m);
}

// s' -> s'' (the sharpness's power compression towards a step).
double sharpness_adjusted(double s, double h) {
  if (s < 0.5) return 0.5 * std::pow(s * 2.0, 1.0 + 10.0 * h);
  if (s > 0.5) return 1.0 - 0.5 * std::pow((1.0 - s) * 2.0, 1.0 + 10.0 * h);
  return s;
}

struct Hermite {
  double h1, h2, h34;
};
Hermite hermite(double s) {
  const double ss = s * s, sss = ss * s;
  return {2 * sss - 3 * ss + 1, -2 * sss + 3 * ss, (sss - 2 * ss + s) + (sss - ss)};
}

// The index k with nodes[k].x < x <= nodes[k+1].x (VTK advances while x > node.x), or -1 / n-1
// beyond the ends.
template <class Node>
long interval_of(const std::vector<Node>& nodes, double x) {
  const auto it = std::lower_bound(nodes.begin(), nodes.end(), x,
                                   [](const Node& n, double v) { return n.x < v; });
  return static_cast<long>(it - nodes.begin()) - 1;
}

// Moreland's Msh: M = |Lab|, s = acos(L/M), h = atan2(b, a).
Rgb lab_to_msh(const Rgb& lab) {
  const double M = std::sqrt(lab[0] * lab[0] + lab[1] * lab[1] + lab[2] * lab[2]);
  const double s = M > 0.001 ? std::acos(lab[0] / M) : 0.0;
  const double h = s > 0.001 ? std::atan2(lab[2], lab[1]) : 0.0;
  return {M, s, h};
}
Rgb msh_to_lab(const Rgb& msh) {
  return {msh[0] * std::cos(msh[1]), msh[0] * std::sin(msh[1]) * std::cos(msh[2]),
          msh[0] * std::sin(msh[1]) * std::sin(msh[2])};
}
double angle_diff(double a1, double a2) {
  double d = std::fabs(a1 - a2);
  while (d >= 2.0 * kPi) d -= 2.0 * kPi;
  if (d > kPi) d = 2.0 * kPi - d;
  return d;
}
// The hue to give an unsaturated colour of magnitude unsat_m next to the saturated `msh`.
double adjust_hue(const Rgb& msh, double unsat_m) {
  if (msh[0] >= unsat_m - 0.1) return msh[2];
  const double spin = msh[1] * std::sqrt(unsat_m * unsat_m - msh[0] * msh[0]) / (msh[0] * std::sin(msh[1]));
  return msh[2] > -0.3 * kPi ? msh[2] + spin : msh[2] - spin;
}
Rgb diverging(double s, const Rgb& rgb1, const Rgb& rgb2) {
  Rgb msh1 = lab_to_msh(rgb_to_lab(rgb1));
  Rgb msh2 = lab_to_msh(rgb_to_lab(rgb2));
  if (msh1[1] > 0.05 && msh2[1] > 0.05 && angle_diff(msh1[2], msh2[2]) > 0.33 * kPi) {
    const double m_mid = std::max({msh1[0], msh2[0], 88.0});
    if (s < 0.5) {
      msh2 = {m_mid, 0.0, 0.0};
      s = 2.0 * s;
    } else {
      msh1 = {m_mid, 0.0, 0.0};
      s = 2.0 * s - 1.0;
    }
  }
  if (msh1[1] < 0.05 && msh2[1] > 0.05)
    msh1[2] = adjust_hue(msh2, msh1[0]);
  else if (msh2[1] < 0.05 && msh1[1] > 0.05)
    msh2[2] = adjust_hue(msh1, msh2[0]);
  Rgb msh;
  for (int j = 0; j < 3; ++j) msh[j] = (1 - s) * msh1[j] + s * msh2[j];
  return lab_to_rgb(msh_to_lab(msh));
}

// Endpoints in the colour space (HSV with the wrap applied to the hues).
std::pair<Rgb, Rgb> hsv_ends(const Rgb& rgb1, const Rgb& rgb2, bool wrap) {
  Rgb a = rgb_to_hsv(rgb1), b = rgb_to_hsv(rgb2);
  if (wrap && (a[0] - b[0] > 0.5 || b[0] - a[0] > 0.5)) (a[0] > b[0] ? a[0] : b[0]) -= 1.0;
  return {a, b};
}

// The colour of the interval from n1 to n2 at parameter s_linear = interval_parameter.
Rgb color_between(const VtkColorTransferFunction& f, const VtkColorNode& n1, const VtkColorNode& n2,
                  double s_linear) {
  const double m = clamp_midpoint(n1.midpoint), h = n1.sharpness;
  double s = midpoint_adjusted(s_linear, m);
  const Rgb& c1 = n1.rgb;
  const Rgb& c2 = n2.rgb;
  if (h > 0.99) return s < 0.5 ? c1 : c2;
  if (f.space == VtkColorSpace::step) return c2;  // VTK_CTF_STEP: no interpolation below h = 0.99
  Rgb out{};
  if (h < 0.01) {  // linear in s' in the colour space; no clipping to [0, 1] in this branch
    switch (f.space) {
      case VtkColorSpace::step:
        return c2;
      case VtkColorSpace::rgb:
        for (int j = 0; j < 3; ++j) out[j] = (1 - s) * c1[j] + s * c2[j];
        return out;
      case VtkColorSpace::hsv: {
        const auto [a, b] = hsv_ends(c1, c2, f.hsv_wrap);
        Rgb hsv;
        for (int j = 0; j < 3; ++j) hsv[j] = (1 - s) * a[j] + s * b[j];
        if (hsv[0] < 0.0) hsv[0] += 1.0;
        return hsv_to_rgb(hsv);
      }
      case VtkColorSpace::lab: {
        const Rgb a = rgb_to_lab(c1), b = rgb_to_lab(c2);
        Rgb lab;
        for (int j = 0; j < 3; ++j) lab[j] = (1 - s) * a[j] + s * b[j];
        return lab_to_rgb(lab);
      }
      case VtkColorSpace::diverging:
        return diverging(s, c1, c2);
    }
  }
  s = sharpness_adjusted(s, h);
  const Hermite w = hermite(s);
  auto curve = [&](const Rgb& a, const Rgb& b) {
    Rgb v;
    for (int j = 0; j < 3; ++j) v[j] = w.h1 * a[j] + w.h2 * b[j] + w.h34 * (1.0 - h) * (b[j] - a[j]);
    return v;
  };
  switch (f.space) {
    case VtkColorSpace::step:
      return c2;
    case VtkColorSpace::rgb:
      out = curve(c1, c2);
      break;
    case VtkColorSpace::hsv: {
      const auto [a, b] = hsv_ends(c1, c2, f.hsv_wrap);
      Rgb hsv = curve(a, b);
      if (hsv[0] < 0.0) hsv[0] += 1.0;
      out = hsv_to_rgb(hsv);
      break;
    }
    case VtkColorSpace::lab:
      out = lab_to_rgb(curve(rgb_to_lab(c1), rgb_to_lab(c2)));
      break;
    case VtkColorSpace::diverging:  // VTK: no Hermite curve here, only the compressed s''
      out = diverging(s, c1, c2);
      break;
  }
  for (double& v : out) v = std::clamp(v, 0.0, 1.0);
  return out;
}

}  // namespace

double VtkPiecewiseFunction::operator()(double x) const {
  const long k = interval_of(nodes, x);
  if (k < 0) return nodes.front().y;
  if (k + 1 >= static_cast<long>(nodes.size())) return nodes.back().y;
  return interval_value(static_cast<std::size_t>(k), x);
}

double VtkPiecewiseFunction::interval_value(std::size_t k, double x) const {
  const VtkPiecewiseNode& n1 = nodes[k];
  const VtkPiecewiseNode& n2 = nodes[k + 1];
  const double m = clamp_midpoint(n1.midpoint), h = n1.sharpness;
  double s = midpoint_adjusted((x - n1.x) / (n2.x - n1.x), m);
  if (h > 0.99) return s < 0.5 ? n1.y : n2.y;
  if (h < 0.01) return (1 - s) * n1.y + s * n2.y;
  s = sharpness_adjusted(s, h);
  const Hermite w = hermite(s);
  const double t = (1.0 - h) * (n2.y - n1.y);
  const double y = w.h1 * n1.y + w.h2 * n2.y + w.h34 * t;
  return std::clamp(y, std::min(n1.y, n2.y), std::max(n1.y, n2.y));
}

Rgb VtkColorTransferFunction::operator()(double x) const {
  // Under the log scale VTK locates x' = 10^(log10 x) among the nodes (GetTable(x, x, 1)) but
  // takes s from log10 x itself.
  const double located = log_scale ? std::pow(10.0, std::log10(x)) : x;
  const long k = interval_of(nodes, located);
  if (k < 0 || !(located >= nodes.front().x)) return nodes.front().rgb;
  if (k + 1 >= static_cast<long>(nodes.size())) return nodes.back().rgb;
  return interval_value(static_cast<std::size_t>(k), x);
}

Rgb VtkColorTransferFunction::interval_value(std::size_t k, double x) const {
  return color_between(*this, nodes[k], nodes[k + 1], interval_parameter(k, x));
}

double VtkColorTransferFunction::interval_parameter(std::size_t k, double x) const {
  const double x1 = nodes[k].x, x2 = nodes[k + 1].x;
  if (!log_scale) return (x - x1) / (x2 - x1);
  const double l1 = std::log10(x1), l2 = std::log10(x2);
  return (std::log10(x) - l1) / (l2 - l1);
}

IntervalShape VtkColorTransferFunction::interval_shape(std::size_t k) const {
  const IntervalShape shape = color_interval_shape(space, nodes[k]);
  // Straight in s is curved in x under the log scale; constants and steps stay what they are.
  if (log_scale && (shape == IntervalShape::linear || shape == IntervalShape::two_linear_pieces) &&
      space != VtkColorSpace::step)
    return IntervalShape::curved;
  return shape;
}

StepLocation VtkColorTransferFunction::step_location(std::size_t k) const {
  const double x1 = nodes[k].x, x2 = nodes[k + 1].x;
  if (!log_scale) return rayint::step_location(x1, x2, nodes[k].midpoint);
  const double m = clamp_midpoint(nodes[k].midpoint);
  auto right_side = [&](double x) { return !(midpoint_adjusted(interval_parameter(k, x), m) < 0.5); };
  double lo = x1, hi = x2;
  while (std::nextafter(lo, hi) < hi) {
    const double mid = lo + (hi - lo) / 2;
    (right_side(mid) ? hi : lo) = mid;
  }
  return {lo, hi};
}

Rgb rgb_to_hsv(const Rgb& c) {
  const double r = c[0], g = c[1], b = c[2];
  double cmax = r, cmin = r;
  if (g > cmax) cmax = g;
  else if (g < cmin) cmin = g;
  if (b > cmax) cmax = b;
  else if (b < cmin) cmin = b;
  const double v = cmax;
  const double s = v > 0.0 ? (cmax - cmin) / cmax : 0.0;
  double h = 0.0;
  if (s > 0) {
    if (r == cmax) h = (1.0 / 6.0) * (g - b) / (cmax - cmin);
    else if (g == cmax) h = 1.0 / 3.0 + (1.0 / 6.0) * (b - r) / (cmax - cmin);
    else h = 2.0 / 3.0 + (1.0 / 6.0) * (r - g) / (cmax - cmin);
    if (h < 0.0) h += 1.0;
  }
  return {h, s, v};
}

Rgb hsv_to_rgb(const Rgb& hsv) {
  const double h = hsv[0], s = hsv[1], v = hsv[2];
  constexpr double third = 1.0 / 3.0, sixth = 1.0 / 6.0, two_thirds = 2.0 / 3.0, five_sixths = 5.0 / 6.0;
  double r, g, b;
  if (h > sixth && h <= third) {
    g = 1.0; r = (third - h) / sixth; b = 0.0;
  } else if (h > third && h <= 0.5) {
    g = 1.0; b = (h - third) / sixth; r = 0.0;
  } else if (h > 0.5 && h <= two_thirds) {
    b = 1.0; g = (two_thirds - h) / sixth; r = 0.0;
  } else if (h > two_thirds && h <= five_sixths) {
    b = 1.0; r = (h - two_thirds) / sixth; g = 0.0;
  } else if (h > five_sixths && h <= 1.0) {
    r = 1.0; b = (1.0 - h) / sixth; g = 0.0;
  } else {
    r = 1.0; g = h / sixth; b = 0.0;
  }
  return {(s * r + (1.0 - s)) * v, (s * g + (1.0 - s)) * v, (s * b + (1.0 - s)) * v};
}

namespace {
constexpr double kRefX = 0.9505, kRefY = 1.000, kRefZ = 1.089;  // D65, 2 degree observer
double srgb_to_linear(double c) { return c > 0.04045 ? std::pow((c + 0.055) / 1.055, 2.4) : c / 12.92; }
double linear_to_srgb(double c) { return c > 0.0031308 ? 1.055 * std::pow(c, 1 / 2.4) - 0.055 : 12.92 * c; }
double lab_f(double t) { return t > 0.008856 ? std::pow(t, 1.0 / 3.0) : 7.787 * t + 16.0 / 116.0; }
double lab_f_inverse(double t) {
  const double t3 = std::pow(t, 3);
  return t3 > 0.008856 ? t3 : (t - 16.0 / 116.0) / 7.787;
}
}  // namespace

Rgb rgb_to_lab(const Rgb& c) {
  const double r = srgb_to_linear(c[0]), g = srgb_to_linear(c[1]), b = srgb_to_linear(c[2]);
  const double x = r * 0.4124 + g * 0.3576 + b * 0.1805;
  const double y = r * 0.2126 + g * 0.7152 + b * 0.0722;
  const double z = r * 0.0193 + g * 0.1192 + b * 0.9505;
  const double fx = lab_f(x / kRefX), fy = lab_f(y / kRefY), fz = lab_f(z / kRefZ);
  return {116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz)};
}

Rgb lab_to_rgb(const Rgb& lab) {
  const double fy = (lab[0] + 16) / 116;
  const double fx = lab[1] / 500 + fy;
  const double fz = fy - lab[2] / 200;
  const double x = kRefX * lab_f_inverse(fx), y = kRefY * lab_f_inverse(fy), z = kRefZ * lab_f_inverse(fz);
  Rgb c{linear_to_srgb(x * 3.2406 + y * -1.5372 + z * -0.4986),
        linear_to_srgb(x * -0.9689 + y * 1.8758 + z * 0.0415),
        linear_to_srgb(x * 0.0557 + y * -0.2040 + z * 1.0570)};
  const double max_value = std::max({c[0], c[1], c[2]});
  if (max_value > 1.0)
    for (double& v : c) v /= max_value;
  for (double& v : c) v = std::max(v, 0.0);
  return c;
}

IntervalShape piecewise_interval_shape(const VtkPiecewiseNode& left) {
  if (left.sharpness > 0.99) return IntervalShape::step;
  if (left.sharpness < 0.01)
    return left.midpoint == 0.5 ? IntervalShape::linear : IntervalShape::two_linear_pieces;
  return IntervalShape::curved;
}

IntervalShape color_interval_shape(VtkColorSpace space, const VtkColorNode& left) {
  if (left.sharpness > 0.99) return IntervalShape::step;
  if (space == VtkColorSpace::step) return IntervalShape::linear;  // the right node's colour throughout
  if (left.sharpness < 0.01 && space == VtkColorSpace::rgb)
    return left.midpoint == 0.5 ? IntervalShape::linear : IntervalShape::two_linear_pieces;
  return IntervalShape::curved;
}

double midpoint_scalar(double x1, double x2, double midpoint) {
  return x1 + clamp_midpoint(midpoint) * (x2 - x1);
}

StepLocation step_location(double x1, double x2, double midpoint) {
  const double m = clamp_midpoint(midpoint);
  auto right_side = [&](double x) { return !(midpoint_adjusted((x - x1) / (x2 - x1), m) < 0.5); };
  double lo = x1, hi = x2;  // right_side(lo) is false (s = 0), right_side(hi) true (s = 1)
  while (std::nextafter(lo, hi) < hi) {
    const double mid = lo + (hi - lo) / 2;
    (right_side(mid) ? hi : lo) = mid;
  }
  return {lo, hi};
}

}  // namespace rayint
