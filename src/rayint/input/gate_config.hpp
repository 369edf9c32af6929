#pragma once
// Reading and validating a gate config (format: docs/gates.md; the project's is cases/gates.json).
// Every problem is an InputError whose message is one line `<file>: <field path>: <what>`.
//
// Relative paths in the config are resolved against the directory that holds the config file
// (for cases/gates.json: cases/), so the gate runs the same from any working directory.
#include <string>
#include <string_view>

#include "rayint/studies/gate.hpp"

namespace rayint {

// `source` names the config in messages and anchors its relative paths. Throws InputError.
GateConfig parse_gate_config_text(std::string_view text, const std::string& source);
GateConfig read_gate_config(const std::string& path);

}  // namespace rayint
