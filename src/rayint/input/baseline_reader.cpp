#include "rayint/input/baseline_reader.hpp"

#include <limits>

#include "rayint/input/json_schema.hpp"
#include "rayint/input/json_source.hpp"

namespace rayint {

Baseline parse_baseline_text(std::string_view text, const std::string& source) {
  using nlohmann::json;
  using json_source::index_path;
  using json_source::member_path;
  const json root = json_source::parse(text, source);
  const JsonSchema s(source);
  s.require_object(root, "");
  s.check_fields(root, "", {"note", "generated_by", "method", "cases"});
  Baseline b;
  b.method = s.non_empty_string(s.required(root, "", "method"), "method");
  b.generated_by = s.string_value(s.required(root, "", "generated_by"), "generated_by");
  const json& cases = s.required(root, "", "cases");
  s.require_object(cases, "cases");
  for (auto it = cases.begin(); it != cases.end(); ++it) {
    const std::string path = member_path("cases", it.key());
    if (!it.value().is_array()) s.fail(path, "must be an array of [r, g, b]");
    std::vector<Rgb>& rays = b.cases[it.key()];
    for (std::size_t i = 0; i < it.value().size(); ++i) {
      const std::string rpath = index_path(path, i);
      const json& ray = it.value()[i];
      s.array_of_size(ray, rpath, 3, "an array of 3 values [r, g, b]");
      Rgb v{};
      for (std::size_t c = 0; c < 3; ++c) {
        const json& x = ray[c];
        const std::string cpath = index_path(rpath, c);
        if (x.is_null()) v[c] = std::numeric_limits<double>::quiet_NaN();
        else if (x.is_string() && x == "inf") v[c] = std::numeric_limits<double>::infinity();
        else if (x.is_string() && x == "-inf") v[c] = -std::numeric_limits<double>::infinity();
        else v[c] = s.finite_number(x, cpath);
      }
      rays.push_back(v);
    }
  }
  return b;
}

Baseline read_baseline_file(const std::string& path) {
  return parse_baseline_text(json_source::read_text_file(path), path);
}

}  // namespace rayint
