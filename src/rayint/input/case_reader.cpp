// Reading and validating case files (format: cases/README.md).
//
// Two stages:
//  1. json_source::parse (input/json_source.hpp) turns the text into a nlohmann::json tree,
//     reporting duplicate keys, overflowing numbers and syntax errors at their field or line.
//  2. A strict schema walk over the tree: required fields, types, finite and non-negative
//     values, non-decreasing breakpoints (a scalar twice: a jump), non-empty arrays, no unknown fields.
//
// Every problem is thrown as one InputError line `<source>: <field path>: <what>`.
//
// Streaming (parse_case_text): the segments, the bulk of a big case, are not kept in the tree.
// json_source streams each rays[i].segments[j] element as soon as it is parsed; it is checked by
// the same schema function (segment) and stored as a Segment (24 bytes instead of nlohmann's
// ~400 for the object, its keys and the pair). A problem found there is held, not thrown, until
// the schema walk reaches that ray's segments, so every file gets the same first message as the
// whole-tree walk (detail::parse_case_text_tree, which tests/test_case_reader.cpp compares it with
// on every case of cases/): syntax errors anywhere, then the walk's order.
#include "rayint/input/case_reader.hpp"

#include "rayint/mesh/quadratic_tets.hpp"

#include "rayint/input/json_schema.hpp"
#include "rayint/input/json_source.hpp"
#include "rayint/input/mesh_case_reader.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <memory>
#include <nlohmann/json.hpp>
#include <utility>
#include <vector>

namespace rayint {
namespace {

using nlohmann::json;

using namespace json_source;  // parse, fail, paths, format_number

// ---------------------------------------------------------------------------------------------
// Stage 2: schema.

// {"length": >= 0, "scalar": [far, near]}.
Segment segment(const JsonSchema& s, const json& j, const std::string& path) {
  s.require_object(j, path);
  s.check_fields(j, path, {"length", "scalar"});
  Segment seg;
  seg.length = s.non_negative(s.required(j, path, "length"), member_path(path, "length"));
  const std::string spath = member_path(path, "scalar");
  const json& sc = s.required(j, path, "scalar");
  s.array_of_size(sc, spath, 2, "a [far, near] pair of numbers");
  seg.scalar_far = s.finite_number(sc[0], index_path(spath, 0));
  seg.scalar_exit = s.finite_number(sc[1], index_path(spath, 1));
  return seg;
}

// The segments of the rays, as streamed: per ray, those read so far, or the first problem.
struct StreamedRay {
  std::vector<Segment> segments;
  std::string error;  // InputError message of the first bad segment; empty: none
};
using StreamedRays = std::vector<StreamedRay>;

// {"background"?: [r, g, b], "segments": [segment, ...]}; with `streamed`, the segments were
// streamed there (the tree holds rays[i].segments empty when it was an array).
Ray ray(const JsonSchema& s, const json& j, const std::string& path, StreamedRay* streamed) {
  s.require_object(j, path);
  s.check_fields(j, path, {"background", "segments"});
  Ray r;
  if (const json* b = s.optional(j, "background"))
    r.background = s.rgb(*b, member_path(path, "background"));
  const std::string spath = member_path(path, "segments");
  const json& segs = s.required(j, path, "segments");
  if (streamed && segs.is_array() && segs.empty()) {
    if (!streamed->error.empty()) throw InputError(streamed->error);
    if (!streamed->segments.empty()) {
      r.segments = std::move(streamed->segments);
      return r;
    }
  }
  s.non_empty_array(segs, spath, "");
  r.segments.reserve(segs.size());
  for (std::size_t i = 0; i < segs.size(); ++i)
    r.segments.push_back(segment(s, segs[i], index_path(spath, i)));
  return r;
}

Case read_case(const JsonSchema& s, const json& root, StreamedRays* streamed) {
  const std::string path;
  s.require_object(root, path);
  s.check_fields(root, path, {"name", "description", "transfer_function", "rays"});
  Case c;
  c.source = s.source();
  c.name = s.non_empty_string(s.required(root, path, "name"), "name");
  if (const json* d = s.optional(root, "description")) c.description = s.string_value(*d, "description");
  c.transfer = s.transfer_functions(s.required(root, path, "transfer_function"), "transfer_function");
  const json& rays = s.required(root, path, "rays");
  s.non_empty_array(rays, "rays", "");
  c.rays.reserve(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) {
    StreamedRay* sr = streamed && i < streamed->size() ? &(*streamed)[i] : nullptr;
    c.rays.push_back(ray(s, rays[i], index_path("rays", i), sr));
  }
  return c;
}

Case parse_case_root(const json& root, const std::string& source, StreamedRays* streamed,
                     const MeshReadOptions& mesh_options, std::optional<TetRepairs>* repairs,
                     std::optional<MeshCase>* own_cells = nullptr) {
  if (repairs) repairs->reset();
  if (own_cells) own_cells->reset();
  if (is_mesh_case(root)) {  // rays traced through a tetrahedral mesh (cases/README.md)
    MeshCase mc = parse_mesh_case(root, source, mesh_options);
    if (mc.cells) {  // cells other than tetrahedra, in their own interpolation: no segments
      if (!own_cells)
        throw InputError(source + ": mesh_file: " + mc.mesh_source +
                         " holds cells other than tetrahedra: this command needs linear segments, which their own "
                         "interpolation does not give (rayint eval, render and check integrate them in it, bench times that "
                         "against VTK's split; eval, render, check and bench take VTK's tetrahedralisation of them "
                         "with --cells split)");
      Case c;
      c.name = mc.name;
      c.description = mc.description;
      c.transfer = mc.transfer;
      *own_cells = std::move(mc);
      return c;
    }
    // Quadratic tetrahedra: their chords stay quadratic (Ray::quadratic); "exact" and the
    // reference integrate them as polynomials, the sampling methods sample them, every other
    // method fails on those rays (mesh/quadratic_methods.hpp).
    if (repairs) *repairs = mc.repairs;
    const TetTraversal mesh(mc.mesh, mc.neighbors, mc.mesh_source);
    return trace_mesh_case(mc, mesh);
  }
  return read_case(JsonSchema(source), root, streamed);
}

}  // namespace

Case parse_case_text(std::string_view text, const std::string& source,
                     const MeshReadOptions& mesh_options, std::optional<TetRepairs>* repairs,
                     std::optional<MeshCase>* own_cells) {
  const JsonSchema schema(source);
  StreamedRays streamed;
  json_source::StreamedArray sink;
  sink.array_path = {"rays", "[]", "segments"};
  sink.element = [&](json& element, const std::vector<std::size_t>& at) {
    const std::size_t i = at[0], k = at[1];
    if (streamed.size() <= i) streamed.resize(i + 1);
    StreamedRay& r = streamed[i];
    if (!r.error.empty()) return;  // the first problem of this ray is the one reported
    try {
      r.segments.push_back(
          segment(schema, element, index_path(member_path(index_path("rays", i), "segments"), k)));
    } catch (const InputError& e) {
      r.error = e.what();
      r.segments = {};
    }
  };
  const json root = json_source::parse(text, source, sink);
  return parse_case_root(root, source, &streamed, mesh_options, repairs, own_cells);
}

namespace detail {
Case parse_case_text_tree(std::string_view text, const std::string& source) {
  return parse_case_root(json_source::parse(text, source), source, nullptr, {}, nullptr);
}
}  // namespace detail

Case read_case_file(const std::string& path, const MeshReadOptions& mesh_options,
                    std::optional<TetRepairs>* repairs, std::optional<MeshCase>* own_cells) {
  const std::string text = json_source::read_text_file(path);
  return parse_case_text(text, path, mesh_options, repairs, own_cells);
}

std::vector<std::string> list_case_files(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  std::vector<std::string> files;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const fs::path& p = it->path();
    if (p.extension() == ".json" && p.filename() != kGateConfigName && it->is_regular_file(ec))
      files.push_back(p.string());
  }
  if (ec) throw InputError(dir + ": cannot list folder (" + ec.message() + ")");
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace rayint
