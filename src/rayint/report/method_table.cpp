#include "rayint/report/method_table.hpp"

namespace rayint {

std::string methods_text(const std::vector<MethodSchema>& methods) {
  std::string out =
      "A method is NAME or NAME:KEY=VALUE:..., e.g. riemann:n=128:order=ftb; a spec outside these\n"
      "ranges is refused before anything runs (exit 2).\n";
  for (const MethodSchema& m : methods) {
    out += "\n" + m.name + "  " + m.about + "\n";
    if (m.params.empty()) out += "    (no parameters)\n";
    for (const MethodParam& p : m.params) {
      std::string line = "    " + p.name + " (" + type_name(p.type) + ", default " +
                         (p.fallback.empty() ? std::string("none") : p.fallback) + "): " +
                         allowed_values(p) + ". " + p.about;
      if (!p.limit.empty()) line += " (max: " + p.limit + ")";
      out += line + "\n";
    }
  }
  return out;
}

nlohmann::json methods_json(const std::vector<MethodSchema>& methods) {
  nlohmann::json list = nlohmann::json::array();
  for (const MethodSchema& m : methods) {
    nlohmann::json params = nlohmann::json::array();
    for (const MethodParam& p : m.params) {
      nlohmann::json j = {{"name", p.name},
                          {"type", type_name(p.type)},
                          {"default", p.fallback.empty() ? nlohmann::json(nullptr) : nlohmann::json(p.fallback)},
                          {"allowed", allowed_values(p)},
                          {"about", p.about}};
      if (p.type == MethodParam::Type::choice) {
        j["choices"] = p.choices;
      } else {
        j["min"] = p.has_min ? nlohmann::json(p.min) : nlohmann::json(nullptr);
        j["min_exclusive"] = p.min_exclusive;
        j["max"] = p.has_max ? nlohmann::json(p.max) : nlohmann::json(nullptr);
        j["max_exclusive"] = p.max_exclusive;
      }
      if (!p.limit.empty()) j["limit"] = p.limit;
      params.push_back(std::move(j));
    }
    list.push_back({{"name", m.name}, {"about", m.about}, {"params", params}});
  }
  return {{"tool", "rayint"}, {"report", "methods"}, {"methods", list}};
}

}  // namespace rayint
