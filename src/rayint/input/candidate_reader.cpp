// Candidate files for `rayint check` (docs/candidate-format.md).
//
// Reading has the same two stages as the case reader (input/case_reader.cpp):
//  1. json_source::parse (input/json_source.hpp) turns the text into a nlohmann::json tree,
//     reporting duplicate keys, overflowing numbers and syntax errors at their field or line;
//  2. a strict schema walk with JsonSchema (input/json_schema.hpp): known fields only, types,
//     three finite numbers per ray (the walk input/candidate_schema.hpp shares with gradcheck's).
// Matching against the case (name, ray count) is a separate step, require_candidate_matches.
// Every problem is one InputError line `<source>: <field path>: <what>`.
#include "rayint/input/candidate_reader.hpp"

#include "rayint/input/candidate_schema.hpp"
#include "rayint/input/json_schema.hpp"
#include "rayint/input/json_source.hpp"

namespace rayint {

Candidate parse_candidate_text(std::string_view text, const std::string& source) {
  // rays[i]: {"index"?: i, "intensity": [r, g, b]}.
  return candidate_schema::parse<Candidate>(
      text, source, "intensity", " of {\"intensity\": [r, g, b]}, one per ray of the case",
      [](const JsonSchema& s, Candidate& c, const nlohmann::json& v, const std::string& path) {
        c.intensity.push_back(candidate_schema::triple(s, v, path));
      });
}

void require_candidate_matches(const Candidate& candidate, const Case& c) {
  candidate_schema::require_case_matches(candidate.source, candidate.case_name, candidate.intensity.size(), c);
}

void require_candidate_matches(const Candidate& candidate, const std::string& case_name,
                               const std::string& case_source, std::size_t rays) {
  candidate_schema::require_case_matches(candidate.source, candidate.case_name, candidate.intensity.size(), case_name,
                                         case_source, rays);
}

Candidate read_candidate_file(const std::string& path, const Case& c) {
  return candidate_schema::read_file(path, c, parse_candidate_text,
                                     static_cast<void (*)(const Candidate&, const Case&)>(require_candidate_matches));
}

Candidate read_case_candidate(const std::string& text, bool is_path, const std::string& source, const Case& c,
                              const MeshCase* own) {
  Candidate candidate = is_path ? parse_candidate_text(json_source::read_text_file(text), text)
                                : parse_candidate_text(text, source);
  if (own)
    require_candidate_matches(candidate, own->name, own->source, evaluation_rays(*own).size());
  else
    require_candidate_matches(candidate, c);
  return candidate;
}

}  // namespace rayint
