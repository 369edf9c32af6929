#pragma once
// The text forms of `rayint gate`: one line per check (studies/gate.hpp), then the verdict; and
// the progress line on stderr.
#include <string>

#include "rayint/studies/gate.hpp"

namespace rayint {

std::string gate_lines(const GateReport& report);
std::string gate_progress_line(const GateProgress& progress);  // "gate: PHASE done/total, N s"

}  // namespace rayint
