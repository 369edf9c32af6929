#pragma once
// Writing a Case in the case-file format (cases/README.md) that read_case_file reads back to the
// same doubles, bit for bit: numbers are written in the shortest form that round-trips.
#include <nlohmann/json.hpp>
#include <string>

#include "rayint/model/ray.hpp"

namespace rayint {

// Transfer functions use the shared form when all three channels are equal, else the
// per-channel form {"r", "g", "b"}. `source` is not written.
nlohmann::ordered_json case_json(const Case& c);
// The same content as case_json, laid out compactly: one line per transfer function (or channel)
// and per segment, with a final newline.
std::string case_text(const Case& c);
// Writes case_text(c) atomically (core/atomic_file.hpp); throws std::runtime_error naming the path.
void write_case_file(const std::string& path, const Case& c);

}  // namespace rayint
