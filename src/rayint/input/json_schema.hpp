#pragma once
// The one strict schema walk of every rayint input file (cases, mesh cases, candidates, gate
// configs, scenes, voxel grids, slab scenes, slab benchmarks): required fields, types, finite and
// non-negative numbers, no unknown fields. Each check throws one InputError line
// `<source>: <field path>: <what>` (json_source::fail), so every reader reports problems the
// same way. Readers compose these checks; they hold no state but the source name.
//
// It walks the trees json_source parses: JsonSchema those of json_source::parse (keys sorted),
// OrderedJsonSchema those of json_source::parse_ordered (keys in file order, so that an object's
// unknown fields and items are met in the order the file gives them).
#include <array>
#include <cstddef>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "rayint/geometry/vec3.hpp"
#include "rayint/model/transfer_function.hpp"
#include "rayint/geometry/camera.hpp"

namespace rayint {

struct PresetImportRequest;  // input/paraview_preset.hpp

template <class Json>
class BasicJsonSchema {
 public:
  using json = Json;
  explicit BasicJsonSchema(std::string source) : source_(std::move(source)) {}
  const std::string& source() const { return source_; }

  [[noreturn]] void fail(const std::string& path, const std::string& what) const;

  void require_object(const json& j, const std::string& path) const;
  // Strict: every key must be one of `allowed`; reported before missing fields, so a typo is
  // named as such.
  void check_fields(const json& object, const std::string& path,
                    std::initializer_list<const char*> allowed) const;
  void check_fields(const json& object, const std::string& path,
                    const std::vector<std::string>& allowed) const;
  const json& required(const json& object, const std::string& path, const char* key) const;
  const json* optional(const json& object, const char* key) const;  // nullptr when absent

  std::string non_empty_string(const json& j, const std::string& path) const;
  std::string string_value(const json& j, const std::string& path) const;
  bool boolean(const json& j, const std::string& path) const;
  double finite_number(const json& j, const std::string& path) const;
  double non_negative(const json& j, const std::string& path) const;  // finite, >= 0; -0 -> +0
  double positive(const json& j, const std::string& path) const;      // finite, > 0
  // A number in [lo, hi] (closed) or (lo, hi) when `open`.
  double in_range(const json& j, const std::string& path, double lo, double hi,
                  bool open = false) const;
  long long integer(const json& j, const std::string& path, long long lo, long long hi) const;
  void non_empty_array(const json& j, const std::string& path, const std::string& of) const;
  // A non-empty array of non-empty strings.
  std::vector<std::string> non_empty_strings(const json& j, const std::string& path) const;
  // An array of exactly n elements (message names `what`).
  void array_of_size(const json& j, const std::string& path, std::size_t n,
                     const std::string& what) const;

  Vec3 vec3(const json& j, const std::string& path) const;            // [x, y, z], finite
  Vec3 direction(const json& j, const std::string& path) const;       // finite, non-zero; normalized
  Rgb rgb(const json& j, const std::string& path) const;              // [r, g, b], finite, >= 0

  // [[scalar, value], ...]: scalars finite and non-decreasing, a scalar at most twice in a row
  // (a jump: left value, then right value), values finite and >= 0.
  PiecewiseLinear points(const json& j, const std::string& path) const;
  // One list for all three channels, or {"r": ..., "g": ..., "b": ...}.
  std::array<PiecewiseLinear, kChannels> channels(const json& j, const std::string& path) const;
  // {"density": channels, "color": channels} (Williams & Max's six transfer functions), or a
  // reference to a ParaView preset {"paraview_preset": FILE, ...} (cases/README.md).
  TransferFunctions transfer_functions(const json& j, const std::string& path) const;
  TransferFunctions preset_transfer_functions(const json& j, const std::string& path) const;
  // The import request of a {"paraview_preset": ...} transfer function (fields checked).
  PresetImportRequest preset_import_request(const json& j, const std::string& path) const;

  // {"position", "look_at", "up"?, "fov_deg" | "ortho_height", "width", "height"}; validated.
  Camera camera(const json& j, const std::string& path) const;

 private:
  std::string source_;
};

using JsonSchema = BasicJsonSchema<nlohmann::json>;
using OrderedJsonSchema = BasicJsonSchema<nlohmann::ordered_json>;
extern template class BasicJsonSchema<nlohmann::json>;
extern template class BasicJsonSchema<nlohmann::ordered_json>;

}  // namespace rayint
