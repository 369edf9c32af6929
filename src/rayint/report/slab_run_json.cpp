#include "rayint/report/slab_run_json.hpp"

namespace rayint {
namespace {

nlohmann::json values_json(const SlabValues& v) {
  return nlohmann::json{{"flux_up_top", v.flux_up_top},
                        {"diffuse_down_bottom", v.diffuse_down_bottom},
                        {"direct_down_bottom", v.direct_down_bottom},
                        {"intensity_up_top", v.intensity_up_top},
                        {"intensity_down_bottom", v.intensity_down_bottom}};
}

}  // namespace

std::string pn_label(int order) {
  const std::string name = "P" + std::to_string(order);
  return order == 1 ? name + " (the diffusion approximation of renderers)" : name;
}

nlohmann::json to_json(const Estimate& e) {
  return {{"mean", e.mean}, {"std_error", e.std_error}, {"lo95", e.lo95()}, {"hi95", e.hi95()}};
}

nlohmann::json slab_problem_json(const SlabProblem& p, const std::string& phase,
                                 const std::string& source) {
  return {{"tau", p.tau},       {"albedo", p.albedo}, {"phase", phase},
          {"source", source},   {"mu0", p.mu0},       {"mu_up", p.mu_up},
          {"mu_down", p.mu_down}, {"ground_albedo", p.ground_albedo}};
}

nlohmann::json slab_scene_json(const std::string& path, const std::string& name, const SlabProblem& p) {
  const bool beam = p.source == SlabSource::beam;
  nlohmann::json j = {{"scene", path}, {"name", name}, {"tau", p.tau}, {"albedo", p.albedo},
                      {"phase", p.phase.name()}, {"source", beam ? "beam" : "isotropic"},
                      {"mu_up", p.mu_up}, {"mu_down", p.mu_down}, {"ground_albedo", p.ground_albedo}};
  if (beam) j["mu0"] = p.mu0;
  return j;
}

nlohmann::json slab_run_json(nlohmann::json j, const SlabRun& run) {
  if (run.doubling) j["doubling"] = values_json(*run.doubling);
  if (run.integral_equation) {
    const SlabIntegralEquationResult& r = *run.integral_equation;
    j["integral_equation"] = values_json(r.values);
    j["integral_equation"]["error_estimate"] = values_json(r.error_estimate);
    j["integral_equation"]["finest_segments"] = r.finest_segments;
  }
  if (run.pn) {
    const PnSolution& s = *run.pn;
    const PnOptions& o = run.options.pn_options;
    nlohmann::json pn = values_json(s.values);
    pn["order"] = o.order;
    pn["boundary"] = o.boundary == PnBoundary::marshak ? "marshak" : "mark";
    pn["label"] = pn_label(o.order);
    pn["seconds"] = run.pn_seconds;
    pn["series_intensity_up_top"] = s.series_up_top;
    pn["series_intensity_down_bottom"] = s.series_down_bottom;
    const PnDiagnostics& d = s.diagnostics;
    pn["diagnostics"] = {{"modes", d.modes}, {"kappa_min", d.kappa_min}, {"kappa_max", d.kappa_max},
                         {"conservative", d.conservative}, {"resonance_averaged", d.resonance_averaged},
                         {"rcond", d.rcond}};
    j["pn"] = pn;
  }
  if (run.single_scattering_closed_form)
    j["single_scattering_closed_form"] = values_json(*run.single_scattering_closed_form);
  if (run.monte_carlo) {
    const SlabEstimates& e = *run.monte_carlo;
    const SlabMonteCarloOptions& m = run.options.mc_options;
    nlohmann::json up = nlohmann::json::array(), down = nlohmann::json::array();
    for (const auto& x : e.intensity_up_top) up.push_back(to_json(x));
    for (const auto& x : e.intensity_down_bottom) down.push_back(to_json(x));
    j["monte_carlo"] = {{"estimator", run.mc_split ? "exact orders 0-1 + MC orders >= 2" : "analog, every order"},
                        {"seed", m.seed},
                        {"max_order", m.max_order},
                        {"photons", e.photons},
                        {"collisions", e.collisions},
                        {"seconds", e.seconds},
                        {"photons_per_second", static_cast<double>(e.photons) / e.seconds},
                        {"flux_up_top", to_json(e.flux_up_top)},
                        {"diffuse_down_bottom", to_json(e.diffuse_down_bottom)},
                        {"direct_down_bottom", to_json(e.direct_down_bottom)},
                        {"intensity_up_top", up},
                        {"intensity_down_bottom", down}};
  }
  return j;
}

}  // namespace rayint
