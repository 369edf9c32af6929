// Reading and validating case files (format: cases/README.md).
//
// Two stages:
//  1. json_source::parse (input/json_source.hpp) turns the text into a nlohmann::json tree,
//     reporting duplicate keys, overflowing numbers and syntax errors at their field or line.
//  2. A strict schema walk over the tree: required fields, types, finite and non-negative
//     values, strictly increasing breakpoints, non-empty arrays, and no unknown fields.
//
// Every problem is thrown as one InputError line `<source>: <field path>: <what>`.
#include "rayint/input/case_reader.hpp"

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

// {"background"?: [r, g, b], "segments": [segment, ...]}.
Ray ray(const JsonSchema& s, const json& j, const std::string& path) {
  s.require_object(j, path);
  s.check_fields(j, path, {"background", "segments"});
  Ray r;
  if (const json* b = s.optional(j, "background"))
    r.background = s.rgb(*b, member_path(path, "background"));
  const std::string spath = member_path(path, "segments");
  const json& segs = s.required(j, path, "segments");
  s.non_empty_array(segs, spath, "");
  r.segments.reserve(segs.size());
  for (std::size_t i = 0; i < segs.size(); ++i)
    r.segments.push_back(segment(s, segs[i], index_path(spath, i)));
  return r;
}

Case read_case(const JsonSchema& s, const json& root) {
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
  for (std::size_t i = 0; i < rays.size(); ++i) c.rays.push_back(ray(s, rays[i], index_path("rays", i)));
  return c;
}

}  // namespace

Case parse_case_text(std::string_view text, const std::string& source, const MeshReadOptions& mesh_options,
                     std::optional<TetRepairs>* repairs) {
  const json root = json_source::parse(text, source);
  if (repairs) repairs->reset();
  if (is_mesh_case(root)) {  // rays traced through a tetrahedral mesh (cases/README.md)
    MeshCase mc = parse_mesh_case(root, source, mesh_options);
    if (repairs) *repairs = mc.repairs;
    const TetTraversal mesh(mc.mesh, mc.mesh_source);
    return trace_mesh_case(mc, mesh);
  }
  return read_case(JsonSchema(source), root);
}

Case read_case_file(const std::string& path, const MeshReadOptions& mesh_options,
                    std::optional<TetRepairs>* repairs) {
  const std::string text = json_source::read_text_file(path);
  return parse_case_text(text, path, mesh_options, repairs);
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
