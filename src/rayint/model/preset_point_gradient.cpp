// The chain rule from the imported nodes to a preset's points (see the header for what is and is
// not differentiable).
#include "rayint/model/preset_point_gradient.hpp"

#include <algorithm>
#include <string>

#include "rayint/core/format.hpp"

namespace rayint {
namespace {

// One VTK curve as the matcher needs it: the points' scalars and each interval's shape.
struct CurvePoints {
  std::vector<double> x, midpoint;
  std::vector<IntervalShape> shape;  // interval k (points k, k + 1)
  std::vector<StepLocation> step;    // for step intervals
};

// d/d(x, value) of every point from the derivatives of the imported nodes `f`, or false with
// `why`. value is the imported node value's own scale (the caller applies d value / d y).
bool chain_to_points(const CurvePoints& curve, const PiecewiseLinear& f, const std::vector<NodeDerivative>& nd,
                     std::vector<double>& dx, std::vector<double>& dv, std::string& why) {
  const std::size_t n = curve.x.size();
  dx.assign(n, 0.0);
  dv.assign(n, 0.0);
  for (std::size_t k = 1; k < n; ++k)
    if (!(curve.x[k] > curve.x[k - 1])) {
      why = "repeated x at point " + std::to_string(k) + " (a jump): not mapped";
      return false;
    }
  for (std::size_t j = 0; j < f.scalar.size(); ++j) {
    const double p = f.scalar[j];
    const double pos_bar = nd[j].position, val_bar = nd[j].value;
    const auto it = std::lower_bound(curve.x.begin(), curve.x.end(), p);
    const std::size_t k = static_cast<std::size_t>(it - curve.x.begin());
    if (k < n && curve.x[k] == p) {  // the point itself
      dx[k] += pos_bar;
      dv[k] += val_bar;
      continue;
    }
    if (k == 0 || k == n) {
      why = "imported node at " + format_number(p) + " lies outside the points' range";
      return false;
    }
    const std::size_t i = k - 1;  // x[i] < p < x[i + 1]
    const double m = std::clamp(curve.midpoint[i], 1e-5, 1.0 - 1e-5);  // VTK's clamp
    const auto through_place = [&](double bar) {  // the node sits at x_i + m (x_i+1 - x_i)
      dx[i] += (1.0 - m) * bar;
      dx[i + 1] += m * bar;
    };
    if (curve.shape[i] == IntervalShape::two_linear_pieces && p == midpoint_scalar(curve.x[i], curve.x[i + 1], curve.midpoint[i])) {
      through_place(pos_bar);
      dv[i] += 0.5 * val_bar;
      dv[i + 1] += 0.5 * val_bar;
      continue;
    }
    if (curve.shape[i] == IntervalShape::step && (p == curve.step[i].below || p == curve.step[i].above)) {
      // The step is a jump: two nodes at step.below, the left value V_i then the right value
      // V_i+1. Its position entry is the jump's, on the first node (the second carries 0: the
      // tie of model/ray_gradient.hpp), so each point gets it once.
      const bool right_node = j > 0 && f.scalar[j - 1] == p;
      through_place(pos_bar);
      (right_node || p == curve.step[i].above ? dv[i + 1] : dv[i]) += val_bar;
      continue;
    }
    why = "interval " + std::to_string(i) + " (x " + format_number(curve.x[i]) + " to " + format_number(curve.x[i + 1]) +
          ") was linearised adaptively: its nodes are not a differentiable function of the points";
    return false;
  }
  return true;
}

}  // namespace

PresetPointGradient preset_point_gradient(const PresetCurves& curves, const TfImport& imported, const RayGradient& g) {
  PresetPointGradient out;
  const std::size_t n_color = curves.color.nodes.size();
  CurvePoints color;
  for (std::size_t k = 0; k < n_color; ++k) {
    color.x.push_back(curves.color.nodes[k].x);
    color.midpoint.push_back(curves.color.nodes[k].midpoint);
    if (k + 1 < n_color && curves.color.nodes[k + 1].x > curves.color.nodes[k].x) {
      color.shape.push_back(curves.color.interval_shape(k));
      color.step.push_back(color.shape.back() == IntervalShape::step ? curves.color.step_location(k) : StepLocation{});
    } else {
      color.shape.push_back(IntervalShape::step);
      color.step.emplace_back();
    }
  }
  CurvePoints opacity;
  for (std::size_t k = 0; k < curves.opacity.nodes.size(); ++k) {
    const VtkPiecewiseNode& node = curves.opacity.nodes[k];
    opacity.x.push_back(node.x);
    opacity.midpoint.push_back(node.midpoint);
    opacity.shape.push_back(piecewise_interval_shape(node));
    opacity.step.push_back(k + 1 < curves.opacity.nodes.size() && opacity.shape.back() == IntervalShape::step
                               ? step_location(node.x, curves.opacity.nodes[k + 1].x, node.midpoint)
                               : StepLocation{});
  }
  // d rho / d y: rho = y (density, nerf_sigma), y / D (unit_distance); sample_distance is not linear.
  double rho_per_y = 1.0;
  bool opacity_linear = true;
  switch (curves.options.convention) {
    case OpacityConvention::density:
    case OpacityConvention::nerf_sigma: break;
    case OpacityConvention::unit_distance: rho_per_y = 1.0 / curves.options.distance; break;
    case OpacityConvention::sample_distance: opacity_linear = false; break;
  }

  out.color_ok = imported.color.exact();
  if (!out.color_ok) out.color_unavailable = "the colour was linearised adaptively (colour space or sharpness): not differentiable in the points";
  out.opacity_ok = curves.opacity_source == PresetOpacitySource::points && opacity_linear && imported.density.exact();
  if (curves.opacity_source != PresetOpacitySource::points)
    out.opacity_unavailable = curves.opacity_source == PresetOpacitySource::default_ramp
                                  ? "no Points: the opacity is ParaView's default ramp over the RGBPoints' range"
                                  : "no Points: a constant opacity was given";
  else if (!opacity_linear)
    out.opacity_unavailable = "the sample_distance convention's density -ln(1 - y)/d is linearised adaptively: not differentiable in the points";
  else if (!imported.density.exact())
    out.opacity_unavailable = "the opacity was linearised adaptively (sharpness in [0.01, 0.99]): not differentiable in the points";

  // Rescaling: X' = b0 + (X - a0) s, s = (b1 - b0)/(a1 - a0), a0 = X_0, a1 = X_n of the colour.
  double s = 1.0, b0 = 0.0, b1 = 1.0;
  if (curves.rescale) {
    const auto& r = *curves.rescale;
    s = (r[3] - r[2]) / (r[1] - r[0]);
    b0 = r[2];
    b1 = r[3];
  }
  for (int c = 0; c < kChannels; ++c) {
    const std::size_t ch = static_cast<std::size_t>(c);
    std::vector<double> cdx, cdv, odx, odv;
    std::string why;
    bool color_chain = out.color_ok && chain_to_points(color, imported.transfer.color[ch], g.color[ch], cdx, cdv, why);
    if (out.color_ok && !color_chain) {
      out.color_ok = false;
      out.color_unavailable = why;
    }
    bool opacity_chain = opacity_linear && imported.density.exact() &&
                         chain_to_points(opacity, imported.transfer.density[ch], g.density[ch], odx, odv, why);
    if (out.opacity_ok && !opacity_chain) {
      out.opacity_ok = false;
      out.opacity_unavailable = why;
    }
    if (out.color_ok && !opacity_chain && curves.opacity_source != PresetOpacitySource::points) {
      // The ramp's ends are RGBPoints' x: without their share the x entries would be wrong.
      out.color_ok = false;
      out.color_unavailable = "the default or constant opacity could not be mapped: " + why;
    }
    if (!color_chain) cdx.assign(n_color, 0.0), cdv.assign(n_color, 0.0);
    // The default ramp's and the constant's nodes sit at the colour's first (and last) x.
    if (opacity_chain && curves.opacity_source != PresetOpacitySource::points) {
      cdx.front() += odx.front();
      if (odx.size() > 1) cdx.back() += odx.back();
      odx.assign(odx.size(), 0.0);
    }
    // Through the rescaling: d X'_j / d X_j = s, and through a0 = X_0 and a1 = X_n every point
    // moves by s (t_j - 1) and -s t_j, t_j = (X'_j - b0)/(b1 - b0).
    if (curves.rescale) {
      double to_first = 0.0, to_last = 0.0;
      const auto through = [&](std::vector<double>& dx, const std::vector<double>& x) {
        for (std::size_t j = 0; j < dx.size(); ++j) {
          const double t = (x[j] - b0) / (b1 - b0);
          to_first += dx[j] * s * (t - 1.0);
          to_last -= dx[j] * s * t;
          dx[j] *= s;
        }
      };
      through(cdx, color.x);
      if (opacity_chain) through(odx, opacity.x);
      cdx.front() += to_first;
      cdx.back() += to_last;
    }
    if (out.color_ok) {
      out.rgb_points[ch].assign(n_color, {0.0, 0.0, 0.0, 0.0});
      for (std::size_t k = 0; k < n_color; ++k) {
        out.rgb_points[ch][k][0] = cdx[k];
        out.rgb_points[ch][k][1 + ch] = cdv[k];
      }
    }
    if (out.opacity_ok) {
      out.points[ch].assign(odx.size(), {0.0, 0.0});
      for (std::size_t k = 0; k < odx.size(); ++k) out.points[ch][k] = {odx[k], odv[k] * rho_per_y};
    }
  }
  if (!out.color_ok)
    for (auto& v : out.rgb_points) v.clear();
  if (!out.opacity_ok)
    for (auto& v : out.points) v.clear();
  return out;
}

}  // namespace rayint
