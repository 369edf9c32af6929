// regimes.cpp -- the samplers behind every named regime (see regimes.hpp for the ranges).
//
// Piece-level samplers draw one channel of one piece: a length, two colours and an incoming
// light, then the densities that put the piece in its regime (set_depth fixes the optical depth
// T = L (rho_exit + rho_far) / 2 and how it is shared between the ends). Their draws, and so the
// pieces a given engine state gives, are fixed: tests and benchmarks depend on them.
//
// Ray-level samplers build a whole case: per-channel piecewise-linear transfer functions over a
// scalar range and one ray of segments through them, chosen so that the ray visits what the
// regime is about (the pulse, many breakpoints, the region beyond the last point). Every value
// they produce is finite and >= 0 where the case format requires it, breakpoints are strictly
// increasing, and every length is > 0, so a sample is a valid case file.
#include "rayint/generators/regimes.hpp"

#include <algorithm>
#include <iterator>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rayint {
namespace {

struct RegimeInfo {
  Regime regime;
  const char* name;
};
const RegimeInfo kRegimes[] = {
    {Regime::thin, "thin"},
    {Regime::moderate, "moderate"},
    {Regime::thick, "thick"},
    {Regime::q2_near_zero_pos, "q2_near_zero_pos"},
    {Regime::q2_near_zero_neg, "q2_near_zero_neg"},
    {Regime::q2_zero, "q2_zero"},
    {Regime::steep_up, "steep_up"},
    {Regime::steep_down, "steep_down"},
    {Regime::zero_density, "zero_density"},
    {Regime::zero_density_end, "zero_density_end"},
    {Regime::huge_kappa_tiny_rho, "huge_kappa_tiny_rho"},
    {Regime::extreme_magnitudes, "extreme_magnitudes"},
    {Regime::narrow_pulse, "narrow_pulse"},
    {Regime::long_ray, "long_ray"},
    {Regime::out_of_range, "out_of_range"},
    {Regime::tau_moderate, "tau_moderate"},
    {Regime::tau_thin, "tau_thin"},
    {Regime::tau_thick, "tau_thick"},
};

const Regime kExtraRegimes[] = {Regime::tau_moderate, Regime::tau_thin, Regime::tau_thick};

bool is_extra_regime(Regime r) {
  return std::find(std::begin(kExtraRegimes), std::end(kExtraRegimes), r) != std::end(kExtraRegimes);
}

double uniform(std::mt19937_64& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}
double log_uniform(std::mt19937_64& rng, double lo, double hi) {
  return std::exp(uniform(rng, std::log(lo), std::log(hi)));
}
bool coin(std::mt19937_64& rng) { return (rng() & 1u) != 0; }

// Sets rho_exit, rho_far so that the optical depth is T and rho_exit/(rho_exit+rho_far) = share.
void set_depth(ChannelPiece& p, double T, double share) {
  const double sum = 2.0 * T / p.length;
  p.rho_exit = sum * share;
  p.rho_far = sum - p.rho_exit;
}

}  // namespace

const std::vector<Regime>& all_regimes() {
  static const std::vector<Regime> all = [] {
    std::vector<Regime> v;
    for (const auto& r : kRegimes)
      if (!is_ray_regime(r.regime) && !is_extra_regime(r.regime)) v.push_back(r.regime);
    return v;
  }();
  return all;
}

const std::vector<Regime>& extra_regimes() {
  static const std::vector<Regime> all(std::begin(kExtraRegimes), std::end(kExtraRegimes));
  return all;
}

const std::vector<Regime>& ray_regimes() {
  static const std::vector<Regime> all = {Regime::narrow_pulse, Regime::long_ray,
                                          Regime::out_of_range};
  return all;
}

const std::vector<Regime>& stress_regimes() {
  static const std::vector<Regime> all = [] {
    std::vector<Regime> v = all_regimes();
    v.insert(v.end(), ray_regimes().begin(), ray_regimes().end());
    return v;
  }();
  return all;
}

bool is_ray_regime(Regime r) {
  return r == Regime::narrow_pulse || r == Regime::long_ray || r == Regime::out_of_range;
}

std::string regime_name(Regime r) {
  for (const auto& info : kRegimes)
    if (info.regime == r) return info.name;
  return "?";
}

bool parse_regime(const std::string& name, Regime& out) {
  for (const auto& info : kRegimes)
    if (name == info.name) {
      out = info.regime;
      return true;
    }
  return false;
}

RegimeSample sample_piece(Regime r, std::mt19937_64& rng) {
  RegimeSample s;
  ChannelPiece& p = s.piece;
  p.length = log_uniform(rng, 1e-3, 1e3);
  p.kappa_exit = log_uniform(rng, 1e-3, 1e3);
  p.kappa_far = log_uniform(rng, 1e-3, 1e3);
  s.incoming = coin(rng) ? 0.0 : log_uniform(rng, 1e-3, 1e3);
  switch (r) {
    case Regime::thin:
      set_depth(p, log_uniform(rng, 1e-16, 1e-3), uniform(rng, 0.0, 1.0));
      break;
    case Regime::moderate:
      set_depth(p, log_uniform(rng, 1e-3, 30.0), uniform(rng, 0.0, 1.0));
      break;
    case Regime::thick:
      set_depth(p, log_uniform(rng, 30.0, 1e6), uniform(rng, 0.0, 1.0));
      break;
    case Regime::tau_moderate:
      set_depth(p, log_uniform(rng, 0.1, 10.0), uniform(rng, 0.0, 1.0));
      break;
    case Regime::tau_thin:
      set_depth(p, log_uniform(rng, 1e-8, 1e-3), uniform(rng, 0.0, 1.0));
      break;
    case Regime::tau_thick:
      set_depth(p, log_uniform(rng, 20.0, 1000.0), uniform(rng, 0.0, 1.0));
      break;
    case Regime::q2_near_zero_pos:
    case Regime::q2_near_zero_neg: {
      const double rel = log_uniform(rng, 1e-16, 1e-4);
      const bool up = r == Regime::q2_near_zero_pos;
      const double share = 0.5 * (1.0 + (up ? rel : -rel));
      set_depth(p, log_uniform(rng, 1e-3, 1e3), share);
      // Below ~1.1e-16 the share rounds to 0.5 and the slope to 0 (q2 == 0: the q2_zero
      // regime). Keep the side: the ends one ulp apart, the smallest slope a double can hold
      // (relative slope 5.5e-17 .. 1.1e-16).
      if (up && !(p.rho_exit > p.rho_far))
        p.rho_exit = std::nextafter(p.rho_far, std::numeric_limits<double>::infinity());
      if (!up && !(p.rho_exit < p.rho_far)) p.rho_exit = std::nextafter(p.rho_far, 0.0);
      break;
    }
    case Regime::q2_zero: {
      const double rho = log_uniform(rng, 1e-6, 1e3) / p.length;
      p.rho_exit = p.rho_far = rho;
      break;
    }
    case Regime::steep_up:
    case Regime::steep_down: {
      const double T = log_uniform(rng, 1e-6, 1e4);
      const double ratio = log_uniform(rng, 1e2, 1e12);
      const double share = (r == Regime::steep_up ? ratio : 1.0) / (1.0 + ratio);
      set_depth(p, T, share);
      break;
    }
    case Regime::zero_density:
      p.rho_exit = p.rho_far = 0.0;
      break;
    case Regime::zero_density_end:
      set_depth(p, log_uniform(rng, 1e-12, 1e4), coin(rng) ? 0.0 : 1.0);
      break;
    case Regime::huge_kappa_tiny_rho:
      p.kappa_exit = log_uniform(rng, 1e6, 1e12);
      p.kappa_far = log_uniform(rng, 1e6, 1e12);
      set_depth(p, log_uniform(rng, 1e-12, 1e-6), uniform(rng, 0.0, 1.0));
      break;
    case Regime::extreme_magnitudes: {
      p.length = log_uniform(rng, 1e-12, 1e6);
      auto value = [&] { return (rng() % 8 == 0) ? 0.0 : log_uniform(rng, 1e-12, 1e12); };
      p.rho_exit = value();
      p.rho_far = value();
      p.kappa_exit = value();
      p.kappa_far = value();
      break;
    }
    case Regime::narrow_pulse:
    case Regime::long_ray:
    case Regime::out_of_range:
      throw std::invalid_argument("regime " + regime_name(r) +
                                  " is ray-level: use sample_ray, not sample_piece");
  }
  return s;
}

namespace {

// ---- ray-level samplers ----------------------------------------------------------------------

// Light entering the far end, per channel: 0 half the time (emission alone), else 1e-3 .. 1e3.
Rgb background(std::mt19937_64& rng) {
  Rgb b{};
  for (double& v : b) v = coin(rng) ? 0.0 : log_uniform(rng, 1e-3, 1e3);
  return b;
}

// A transfer-function value: 0 with probability 1/8 (zero density or colour on a stretch),
// else log-uniform in [lo, hi].
double value_or_zero(std::mt19937_64& rng, double lo, double hi) {
  return rng() % 8 == 0 ? 0.0 : log_uniform(rng, lo, hi);
}

// s + w, or the next double above s if that rounds back to s: breakpoints stay strictly
// increasing however narrow the requested width.
double step_above(double s, double w) {
  const double t = s + w;
  return t > s ? t : std::nextafter(s, std::numeric_limits<double>::infinity());
}

// Width of one flank of a pulse: one ulp (1/8 of the time), else 1e-15 .. 1e-12.
double pulse_width(std::mt19937_64& rng) {
  return rng() % 8 == 0 ? 0.0 : log_uniform(rng, 1e-15, 1e-12);
}

// A function on [0, 1] with one narrow pulse at `center` (in [0.25, 0.75]): base values at 0,
// just before the rise, just after the fall and at 1; the peak, held over a plateau of width 0
// (half the time) or another pulse_width. The peak is log-uniform in [peak_lo, peak_hi], or 0
// (1/4 of the time: a narrow gap in an otherwise dense or bright stretch).
PiecewiseLinear pulse_function(std::mt19937_64& rng, double center, double base_lo,
                               double base_hi, double peak_lo, double peak_hi) {
  const bool gap = rng() % 4 == 0;
  auto base = [&] { return gap ? log_uniform(rng, base_lo, base_hi) : value_or_zero(rng, base_lo, base_hi); };
  const double peak = gap ? 0.0 : log_uniform(rng, peak_lo, peak_hi);
  const double rise = pulse_width(rng);
  const double s_rise = rise > 0.0 ? center - rise : std::nextafter(center, 0.0);
  PiecewiseLinear f;
  f.scalar = {0.0, s_rise, center};
  f.value = {base(), base(), peak};
  if (coin(rng)) {  // plateau
    f.scalar.push_back(step_above(center, pulse_width(rng)));
    f.value.push_back(peak);
  }
  f.scalar.push_back(step_above(f.scalar.back(), pulse_width(rng)));
  f.value.push_back(base());
  f.scalar.push_back(1.0);
  f.value.push_back(base());
  return f;
}

PiecewiseLinear linear_function(double s0, double v0, double s1, double v1) {
  return {{s0, s1}, {v0, v1}};
}

// Scalar drawn to make a segment meet the pulses: anywhere in [0, 1] (1/4), exactly on a
// breakpoint (1/4), strictly between two adjacent breakpoints (1/4, which for a pulse means on
// its flank or plateau), or one ulp beside a breakpoint (1/4).
double pulse_scalar(std::mt19937_64& rng, const std::vector<double>& bps) {
  const std::size_t k = rng() % bps.size();
  switch (rng() % 4) {
    case 0: return uniform(rng, 0.0, 1.0);
    case 1: return bps[k];
    case 2: {
      if (k + 1 == bps.size()) return bps[k];
      const double s = bps[k] + uniform(rng, 0.0, 1.0) * (bps[k + 1] - bps[k]);
      return std::min(std::max(s, bps[k]), bps[k + 1]);
    }
    default:
      return std::nextafter(bps[k], coin(rng) ? 2.0 : -1.0);
  }
}

RaySample sample_narrow_pulse(std::mt19937_64& rng) {
  RaySample out;
  const bool shared_center = coin(rng);
  const double center = uniform(rng, 0.25, 0.75);
  for (int c = 0; c < kChannels; ++c) {
    const double cc = shared_center ? center : uniform(rng, 0.25, 0.75);
    // Density: base 1e-3 .. 10, peak 1 .. 1e12, so crossing a 1e-12 wide pulse along a unit
    // length adds an optical depth of up to ~1 and sitting on its top up to 1e14.
    out.transfer.density[c] = pulse_function(rng, cc, 1e-3, 10.0, 1.0, 1e12);
    // Colour: a pulse at the same place (half the time, peak up to 1e6) or a line.
    out.transfer.color[c] =
        coin(rng) ? pulse_function(rng, cc, 1e-2, 1e2, 1e-2, 1e6)
                  : linear_function(0.0, log_uniform(rng, 1e-2, 1e2), 1.0, log_uniform(rng, 1e-2, 1e2));
  }
  out.ray.background = background(rng);
  const std::vector<double> bps = out.transfer.breakpoints();
  const int n = 1 + static_cast<int>(rng() % 6);
  for (int i = 0; i < n; ++i) {
    Segment seg;
    seg.length = log_uniform(rng, 1e-2, 1e2);
    switch (rng() % 4) {
      case 0:  // across every pulse, either way
      case 1: {
        const double lo = uniform(rng, 0.0, 0.2), hi = uniform(rng, 0.8, 1.0);
        seg.scalar_far = coin(rng) ? lo : hi;
        seg.scalar_exit = seg.scalar_far == lo ? hi : lo;
        break;
      }
      case 2:  // ends on, beside or inside a pulse
        seg.scalar_far = pulse_scalar(rng, bps);
        seg.scalar_exit = pulse_scalar(rng, bps);
        break;
      default:  // constant scalar (w = 0) on, beside or inside a pulse
        seg.scalar_far = seg.scalar_exit = pulse_scalar(rng, bps);
        break;
    }
    out.ray.segments.push_back(seg);
  }
  return out;
}

constexpr int kLongRaySegments = 10000;

// Sorted distinct scalars: lo, hi and `interior` uniform points between them.
std::vector<double> breakpoints_between(std::mt19937_64& rng, double lo, double hi, int interior) {
  std::vector<double> s = {lo, hi};
  for (int i = 0; i < interior; ++i) s.push_back(uniform(rng, lo, hi));
  std::sort(s.begin(), s.end());
  s.erase(std::unique(s.begin(), s.end()), s.end());
  return s;
}

// Values at `scalars`: shared by all channels (half the time) or drawn per channel.
std::array<PiecewiseLinear, kChannels> functions_at(std::mt19937_64& rng,
                                                    const std::vector<double>& scalars,
                                                    double lo, double hi) {
  std::array<PiecewiseLinear, kChannels> f;
  const bool shared = coin(rng);
  for (int c = 0; c < kChannels; ++c) {
    if (shared && c > 0) {
      f[c] = f[0];
      continue;
    }
    f[c].scalar = scalars;
    for (std::size_t k = 0; k < scalars.size(); ++k) f[c].value.push_back(value_or_zero(rng, lo, hi));
  }
  return f;
}

// Reflects s into [0, 1].
double reflect01(double s) {
  if (s < 0.0) s = -s;
  if (s > 1.0) s = 2.0 - s;
  return std::min(std::max(s, 0.0), 1.0);
}

RaySample sample_long_ray(std::mt19937_64& rng) {
  RaySample out;
  const std::vector<double> scalars =
      breakpoints_between(rng, 0.0, 1.0, static_cast<int>(rng() % 11));  // 2 .. 12 points
  // Lengths log-uniform in len_scale * [0.1, 10] (mean 2.15 len_scale); densities log-uniform in
  // rho_scale * [0.1, 10], with rho_scale chosen so the whole ray's optical depth is about D.
  const double depth = log_uniform(rng, 1e-2, 1e3);
  const double len_scale = log_uniform(rng, 1e-3, 1e3);
  const double mean_length = len_scale * 9.9 / std::log(100.0);
  const double rho_scale = depth / (kLongRaySegments * mean_length * 2.15);
  out.transfer.density = functions_at(rng, scalars, 0.1 * rho_scale, 10.0 * rho_scale);
  out.transfer.color = functions_at(rng, scalars, 1e-2, 1e2);
  out.ray.background = background(rng);
  // The scalar performs a reflected random walk with steps up to sigma; 1/64 of the faces are
  // discontinuous (the next segment starts elsewhere) and 1/32 of the segments have w = 0.
  const double sigma = log_uniform(rng, 1e-3, 1e-1);
  double s = uniform(rng, 0.0, 1.0);
  out.ray.segments.reserve(kLongRaySegments);
  for (int i = 0; i < kLongRaySegments; ++i) {
    Segment seg;
    seg.length = len_scale * log_uniform(rng, 0.1, 10.0);
    seg.scalar_far = rng() % 64 == 0 ? uniform(rng, 0.0, 1.0) : s;
    seg.scalar_exit =
        rng() % 32 == 0 ? seg.scalar_far : reflect01(seg.scalar_far + sigma * uniform(rng, -1.0, 1.0));
    s = seg.scalar_exit;
    out.ray.segments.push_back(seg);
  }
  return out;
}

RaySample sample_out_of_range(std::mt19937_64& rng) {
  RaySample out;
  const double lo = uniform(rng, -1.0, 1.0);
  const double span = log_uniform(rng, 1e-3, 1e3);
  const double hi = lo + span;
  // 1 .. 5 points; a single point is a constant function.
  const int points = 1 + static_cast<int>(rng() % 5);
  const std::vector<double> scalars =
      points == 1 ? std::vector<double>{lo} : breakpoints_between(rng, lo, hi, points - 2);
  out.transfer.density = functions_at(rng, scalars, 1e-3, 1e2);
  out.transfer.color = functions_at(rng, scalars, 1e-2, 1e2);
  out.ray.background = background(rng);
  // below / above the range by span * 1e-12 .. 1e6, inside it, or exactly on an end.
  auto scalar = [&](int kind) {
    switch (kind) {
      case 0: return lo - span * log_uniform(rng, 1e-12, 1e6);
      case 1: return hi + span * log_uniform(rng, 1e-12, 1e6);
      case 2: return uniform(rng, lo, hi);
      case 3: return lo;
      default: return hi;
    }
  };
  const int n = 1 + static_cast<int>(rng() % 6);
  for (int i = 0; i < n; ++i) {
    Segment seg;
    seg.length = log_uniform(rng, 1e-3, 1e2);
    // The first segment starts outside the range, so every ray goes there.
    seg.scalar_far = scalar(i == 0 ? static_cast<int>(rng() % 2) : static_cast<int>(rng() % 5));
    seg.scalar_exit = rng() % 8 == 0 ? seg.scalar_far : scalar(static_cast<int>(rng() % 5));
    out.ray.segments.push_back(seg);
  }
  return out;
}

}  // namespace

RaySample piece_as_ray(const RegimeSample& s) {
  const ChannelPiece& p = s.piece;
  RaySample out;
  for (int c = 0; c < kChannels; ++c) {
    out.transfer.density[c] = linear_function(0.0, p.rho_far, 1.0, p.rho_exit);
    out.transfer.color[c] = linear_function(0.0, p.kappa_far, 1.0, p.kappa_exit);
  }
  out.ray.background = {s.incoming, s.incoming, s.incoming};
  out.ray.segments = {Segment{p.length, 0.0, 1.0}};
  return out;
}

RaySample sample_ray(Regime r, std::mt19937_64& rng) {
  switch (r) {
    case Regime::narrow_pulse: return sample_narrow_pulse(rng);
    case Regime::long_ray: return sample_long_ray(rng);
    case Regime::out_of_range: return sample_out_of_range(rng);
    default: return piece_as_ray(sample_piece(r, rng));
  }
}

std::vector<ChannelPiece> mixed_regime_pieces(std::size_t count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const std::vector<Regime>& regimes = all_regimes();
  std::vector<ChannelPiece> out;
  out.reserve(count);
  for (std::size_t i = 0; i < count; ++i) out.push_back(sample_piece(regimes[i % regimes.size()], rng).piece);
  return out;
}

}  // namespace rayint
