#pragma once
// Reading scene files (format: docs/scenes.md). Strict: unknown fields, wrong types, negative or
// non-finite numbers, unknown effects or methods are each one InputError line
// `<file>: <field path>: <what>` (input/json_schema.hpp).
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "rayint/input/json_schema.hpp"
#include "rayint/scene/scene.hpp"

namespace rayint {

// `base_dir` resolves relative file names (background image, grid files).
Scene parse_scene(const nlohmann::json& root, const std::string& source, const std::string& base_dir);
Scene parse_scene_text(std::string_view text, const std::string& source, const std::string& base_dir);
Scene read_scene_file(const std::string& path);

// Medium types ("medium": {"type": NAME, ...}). To add one, add a line to medium_types() in
// scene_reader.cpp; the parser validates its own fields (the "type" key is already checked).
struct MediumType {
  std::string name;
  std::function<std::shared_ptr<const DensityField>(const nlohmann::json& j, const JsonSchema& schema,
                                                    const std::string& path, const std::string& base_dir)>
      parse;
};
const std::vector<MediumType>& medium_types();

}  // namespace rayint
