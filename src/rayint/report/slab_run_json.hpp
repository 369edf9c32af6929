#pragma once
// The JSON of `rayint slab` on one problem or a slab scene: the problem, then each method's
// values (doubling, integral equation, P_N, single-scattering closed form, Monte Carlo estimates).
#include <nlohmann/json.hpp>
#include <string>

#include "rayint/scattering/slab_run.hpp"

namespace rayint {

nlohmann::json to_json(const Estimate& e);  // mean, std_error, lo95, hi95

// "P15"; P1 is called what it is: "P1 (the diffusion approximation of renderers)".
std::string pn_label(int order);

// The problem as given by options: `phase` and `source` as the user wrote them.
nlohmann::json slab_problem_json(const SlabProblem& p, const std::string& phase,
                                 const std::string& source);
// The problem of a slab scene file (mu0 only for a beam).
nlohmann::json slab_scene_json(const std::string& path, const std::string& name, const SlabProblem& p);

// `problem` (one of the two above) with the results of `run` added.
nlohmann::json slab_run_json(nlohmann::json problem, const SlabRun& run);

}  // namespace rayint
