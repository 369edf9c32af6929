#pragma once
// The one place where stress and gate results become JSON, and where a stress run's worst
// samples become case files. Non-finite numbers are written as null (JSON has no NaN/Inf).
#include <nlohmann/json.hpp>
#include <string>

#include "rayint/studies/gate.hpp"
#include "rayint/studies/stress.hpp"

namespace rayint {

nlohmann::ordered_json to_json(const ErrorStats& s);
nlohmann::ordered_json to_json(const MethodStress& m);
nlohmann::ordered_json to_json(const RegimeStress& r);
nlohmann::ordered_json to_json(const StressReport& r);
nlohmann::ordered_json to_json(const GateReport& r);

// Writes each regime's and method's worst sample (and worst finite one, if any) as
// DIR/<case name>.json (the case name is stress-<regime>-<method>[-finite]) and records the
// path in `worst.file` (`worst_finite.file`). Creates DIR if needed; files
// are written atomically. Throws std::runtime_error naming the path on failure.
void write_worst_cases(StressReport& report, const std::string& dir);

}  // namespace rayint
