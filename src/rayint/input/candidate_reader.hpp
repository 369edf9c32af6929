#pragma once
// Candidate files for `rayint check` -- another renderer's per-ray intensities (format:
// docs/candidate-format.md; the diff the check writes: report/check_json.hpp). Every input problem is one
// InputError line `<candidate file>: <field path>: <what>`, like the case reader's.
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "rayint/studies/check.hpp"
#include "rayint/core/error.hpp"

namespace rayint {

// Structure only: known fields, types, one [r, g, b] triple of finite numbers per ray.
// `source` is the file name used in messages. Throws InputError.
Candidate parse_candidate_text(std::string_view text, const std::string& source);

// The candidate answers case `c`: the same case name and one entry per ray. Throws InputError
// naming the candidate's file and field (and the case file).
void require_candidate_matches(const Candidate& candidate, const Case& c);

// Reads `path`, parses it and requires it to match `c`. Throws InputError.
Candidate read_candidate_file(const std::string& path, const Case& c);

}  // namespace rayint
