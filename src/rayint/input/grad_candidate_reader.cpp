// Candidate gradients for `rayint gradcheck` (declared in input/candidate_reader.hpp):
// json_source::parse, then a strict schema walk (input/json_schema.hpp), as
// input/candidate_reader.cpp does for intensities. An entry may be null: NaN in the candidate,
// an entry the renderer says it cannot give (grad_check counts it as not passed).
#include "rayint/input/candidate_reader.hpp"

#include "rayint/input/candidate_schema.hpp"
#include "rayint/input/json_schema.hpp"
#include "rayint/input/json_source.hpp"

namespace rayint {

using json_source::fail;

namespace {

using nlohmann::json;
using json_source::index_path;
using json_source::member_path;

constexpr const char* kChannelNames[kChannels] = {"r", "g", "b"};

using candidate_schema::finite_or_null;
using candidate_schema::triple;


void node_blocks(const JsonSchema& s, const json& j, const std::string& path,
                 std::array<std::vector<NodeDerivative>, kChannels>& out) {
  s.require_object(j, path);
  s.check_fields(j, path, {"r", "g", "b"});
  for (int c = 0; c < kChannels; ++c) {
    const std::string cpath = member_path(path, kChannelNames[c]);
    const json& list = s.required(j, path, kChannelNames[c]);
    s.non_empty_array(list, cpath, " of [d position, d value], one per node");
    for (std::size_t k = 0; k < list.size(); ++k) {
      const std::string npath = index_path(cpath, k);
      s.array_of_size(list[k], npath, 2, "an array of 2 numbers [d position, d value]");
      out[c].push_back(
          {finite_or_null(s, list[k][0], index_path(npath, 0)), finite_or_null(s, list[k][1], index_path(npath, 1))});
    }
  }
}

RayGradient gradient(const JsonSchema& s, const json& j, const std::string& path) {
  s.require_object(j, path);
  s.check_fields(j, path, {"background", "length", "scalar", "density", "color"});
  RayGradient g;
  g.background = triple(s, s.required(j, path, "background"), member_path(path, "background"), true);
  const std::string lpath = member_path(path, "length"), spath = member_path(path, "scalar");
  const json& length = s.required(j, path, "length");
  const json& scalar = s.required(j, path, "scalar");
  if (!length.is_array()) s.fail(lpath, "must be an array of [r, g, b], one per segment");
  if (!scalar.is_array()) s.fail(spath, "must be an array of [[far r, g, b], [exit r, g, b]], one per segment");
  if (scalar.size() != length.size())
    s.fail(spath, "has " + std::to_string(scalar.size()) + " entries but length has " +
                      std::to_string(length.size()) + " (one per segment each)");
  for (std::size_t i = 0; i < length.size(); ++i) {
    g.length.push_back(triple(s, length[i], index_path(lpath, i), true));
    const std::string p = index_path(spath, i);
    s.array_of_size(scalar[i], p, 2, "an array [[far r, g, b], [exit r, g, b]]");
    g.scalar_far.push_back(triple(s, scalar[i][0], index_path(p, 0), true));
    g.scalar_exit.push_back(triple(s, scalar[i][1], index_path(p, 1), true));
  }
  node_blocks(s, s.required(j, path, "density"), member_path(path, "density"), g.density);
  node_blocks(s, s.required(j, path, "color"), member_path(path, "color"), g.color);
  return g;
}

}  // namespace

GradCandidate parse_grad_candidate_text(std::string_view text, const std::string& source) {
  // rays[i]: {"index"?: i, "gradient": GRADIENT}.
  return candidate_schema::parse<GradCandidate>(
      text, source, "gradient", " of {\"gradient\": {...}}, one per ray of the case",
      [](const JsonSchema& s, GradCandidate& c, const json& g, const std::string& path) {
        c.rays.push_back(gradient(s, g, path));
      });
}

void require_grad_candidate_matches(const GradCandidate& cand, const Case& c) {
  candidate_schema::require_case_matches(cand.source, cand.case_name, cand.rays.size(), c);
  for (std::size_t i = 0; i < c.rays.size(); ++i) {
    const std::string path = member_path(index_path("rays", i), "gradient");
    const RayGradient& g = cand.rays[i];
    const std::size_t m = c.rays[i].segments.size();
    if (g.length.size() != m)
      fail(cand.source, member_path(path, "length"),
           "has " + std::to_string(g.length.size()) + " entries but ray " + std::to_string(i) + " of " +
               c.source + " has " + std::to_string(m) + " segments");
    for (int ch = 0; ch < kChannels; ++ch) {
      for (const bool density : {true, false}) {
        const std::size_t want = (density ? c.transfer.density : c.transfer.color)[ch].scalar.size();
        const std::size_t have = (density ? g.density : g.color)[ch].size();
        if (have != want)
          fail(cand.source, member_path(member_path(path, density ? "density" : "color"), kChannelNames[ch]),
               "has " + std::to_string(have) + " nodes but the case's " + (density ? "density " : "color ") +
                   kChannelNames[ch] + " has " + std::to_string(want));
      }
    }
  }
}

GradCandidate read_grad_candidate_file(const std::string& path, const Case& c) {
  return candidate_schema::read_file(path, c, parse_grad_candidate_text, require_grad_candidate_matches);
}

}  // namespace rayint
