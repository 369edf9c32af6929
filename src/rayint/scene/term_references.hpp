#pragma once
// The references of the scene terms: adaptive quadrature along the viewing ray (and, with
// shadows, nested along the light's path at every node), independent of every approximation.
//
//   term = int_{t_enter}^{t_exit} S(t) exp(-tau(t)) dt,  tau(t) = int_{t_enter}^{t} sigma_t dt'
// (Max 1995 Eq. for absorption plus emission, with S the source of the effect: g for emission,
// sigma_s sum_L p E T_L for single scattering, the shading source for shading), and T = exp(-tau)
// over the whole span for absorption.
//
// Method: global adaptive Gauss-Kronrod 7-15 (nodes and weights from Boost.Math) on Rgb-valued
// integrands, started from panels no longer than the medium's feature_length() (one panel whose
// nodes all miss a feature would report a zero error and stop); the interval with the largest error estimate |K15 - G7| is bisected until every
// channel's total estimate is <= max(atol, rtol |value|) or the interval budget is spent
// (converged = false then, never silently). tau(t) at an outer node is tau at the nearest of 64
// knots (each knot-to-knot depth adaptive to rtol / 10) plus an adaptive integral from the knot.
// The light depth T_L = exp(-int sigma_t) along the light's path is an adaptive integral at each
// node (nested quadrature). Integrands are evaluated in double, so the reference is the exact
// integral of the double-precision medium to about rtol (tests/test_scene_closed_forms.cpp
// checks it against the closed forms to 1e-9 relative).
#include <functional>

#include "rayint/scene/effect.hpp"

namespace rayint {

struct QuadratureResult {
  Rgb value{};
  Rgb error{};  // absolute estimate
  long long evaluations = 0;
  bool converged = true;
};

QuadratureResult integrate_adaptive(const std::function<Rgb(double)>& f, double a, double b,
                                    const QuadratureOptions& options);

// The light transmittance from light `light` to p by adaptive quadrature of its optical depth.
Rgb reference_light_transmittance(const Scene& scene, std::size_t light, const Vec3& p,
                                  const QuadratureOptions& options, long long& evaluations,
                                  bool& converged);

// A source term S(p, optics, light transmittance function) per unit length.
using LightTransmittanceFn = std::function<Rgb(std::size_t light, const Vec3& p)>;
using SourceFn = std::function<Rgb(const Vec3& p, const Optics& optics, const LightTransmittanceFn&)>;

// The reference of a source term along `ray` (attenuated by the view depth when `absorption`,
// shadowed by the reference light depth when `shadows`).
ReferenceValue reference_source_term(const Scene& scene, const ViewRay& ray, const SourceFn& source,
                                     bool absorption, bool shadows);

// The reference view transmittance over the whole span, per channel.
ReferenceValue reference_transmittance(const Scene& scene, const ViewRay& ray);

}  // namespace rayint
