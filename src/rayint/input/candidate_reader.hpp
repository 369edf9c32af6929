#pragma once
// Candidate files: another renderer's answers for a case, checked against rayint's.
//  - `rayint check`: per-ray intensities (format: docs/candidate-format.md; the diff the check
//    writes: report/check_json.hpp). Read by input/candidate_reader.cpp.
//  - `rayint gradcheck` (issue 28; format: docs/gradients.md): per-ray gradients,
//      {"case": NAME, "renderer"?: TEXT, "rays": [{"index"?: i, "gradient": GRADIENT}, ...]}
//    with GRADIENT in the layout of report/grad_json.hpp (what `rayint grad` writes under
//    methods.<m>.gradient); an entry may be null, a derivative the renderer cannot give (stored
//    as NaN; gradcheck counts it as not passed). Read by input/grad_candidate_reader.cpp.
// Every input problem is one InputError line `<candidate file>: <field path>: <what>`, like the
// case reader's.
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "rayint/mesh/mesh_case.hpp"
#include "rayint/studies/check.hpp"
#include "rayint/studies/grad_study.hpp"
#include "rayint/core/error.hpp"

namespace rayint {

// Structure only: known fields, types, one [r, g, b] triple of finite numbers per ray.
// `source` is the file name used in messages. Throws InputError.
Candidate parse_candidate_text(std::string_view text, const std::string& source);

// The candidate answers case `c`: the same case name and one entry per ray. Throws InputError
// naming the candidate's file and field (and the case file).
void require_candidate_matches(const Candidate& candidate, const Case& c);
// The same for a case given by its name, file and ray count (a mesh case of cells in their own
// interpolation: its evaluation rays, mesh/mesh_case.hpp).
void require_candidate_matches(const Candidate& candidate, const std::string& case_name,
                               const std::string& case_source, std::size_t rays);

// Reads `path`, parses it and requires it to match `c`. Throws InputError.
Candidate read_candidate_file(const std::string& path, const Case& c);

// The candidate of `rayint check` and Python's check() for a case as the case reader returned
// it: with `own` (a mesh of cells other than tetrahedra, in their own interpolation) one entry per
// evaluation ray of `*own`, else one per ray of `c`. `text` is the candidate file's path when
// `is_path`, else the document itself, named `source` in messages. Throws InputError.
Candidate read_case_candidate(const std::string& text, bool is_path, const std::string& source, const Case& c,
                              const MeshCase* own);

// Gradients. Structure only: known fields, types, finite numbers or null, consistent block sizes
// within a ray. Throws InputError.
GradCandidate parse_grad_candidate_text(std::string_view text, const std::string& source);
// The candidate answers case `c`: same name, one entry per ray, per ray as many segments as the
// ray and per channel as many nodes as the case's density and color functions. Throws InputError.
void require_grad_candidate_matches(const GradCandidate& candidate, const Case& c);
GradCandidate read_grad_candidate_file(const std::string& path, const Case& c);

}  // namespace rayint
