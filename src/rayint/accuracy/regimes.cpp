#include "rayint/accuracy/regimes.hpp"

#include <cmath>

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
};

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
    for (const auto& r : kRegimes) v.push_back(r.regime);
    return v;
  }();
  return all;
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
    case Regime::q2_near_zero_pos:
    case Regime::q2_near_zero_neg: {
      const double rel = log_uniform(rng, 1e-16, 1e-4);
      const double share = 0.5 * (1.0 + (r == Regime::q2_near_zero_pos ? rel : -rel));
      set_depth(p, log_uniform(rng, 1e-3, 1e3), share);
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
  }
  return s;
}

}  // namespace rayint
