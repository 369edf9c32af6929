#pragma once
// Candidate gradient files for `rayint gradcheck` (issue 28; format: docs/gradients.md):
//   {"case": NAME, "renderer"?: TEXT, "rays": [{"index"?: i, "gradient": GRADIENT}, ...]}
// with GRADIENT in the layout of report/grad_json.hpp (what `rayint grad` writes under
// methods.<m>.gradient). Every input problem is one InputError line
// `<candidate file>: <field path>: <what>`, like the other readers'.
#include <string>
#include <string_view>

#include "rayint/core/error.hpp"
#include "rayint/studies/grad_study.hpp"

namespace rayint {

// Structure only: known fields, types, finite numbers, consistent block sizes within a ray.
// Throws InputError.
GradCandidate parse_grad_candidate_text(std::string_view text, const std::string& source);

// The candidate answers case `c`: same name, one entry per ray, per ray as many segments as the
// ray and per channel as many nodes as the case's density and color functions. Throws InputError.
void require_grad_candidate_matches(const GradCandidate& candidate, const Case& c);

GradCandidate read_grad_candidate_file(const std::string& path, const Case& c);

}  // namespace rayint
