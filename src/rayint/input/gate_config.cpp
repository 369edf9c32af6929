// Reading and validating a gate config (format: docs/gates.md). Parsed by json_source like every
// input file (duplicate keys, overflowing numbers and syntax errors reported at their field or
// line), then walked strictly with the one schema walker (input/json_schema.hpp): known fields
// only, required fields present, limits finite and >= 0, methods that parse and can be built,
// regimes that exist, case patterns that match files, and case names that are in the corpus.
#include "rayint/core/limits.hpp"
#include "rayint/input/gate_config.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "rayint/input/case_reader.hpp"
#include "rayint/input/json_schema.hpp"
#include "rayint/input/json_source.hpp"

namespace rayint {
namespace {

using json = nlohmann::ordered_json;  // keeps the config's order: checks are reported in it
using json_source::index_path;
using json_source::member_path;
namespace fs = std::filesystem;

// '*' (any run of characters) and '?' (one character) against a whole file name.
bool glob_match(const std::string& pattern, const std::string& name) {
  std::size_t p = 0, n = 0, star = std::string::npos, mark = 0;
  while (n < name.size()) {
    if (p < pattern.size() && (pattern[p] == '?' || pattern[p] == name[n])) {
      ++p;
      ++n;
    } else if (p < pattern.size() && pattern[p] == '*') {
      star = p++;
      mark = n;
    } else if (star != std::string::npos) {
      p = star + 1;
      n = ++mark;
    } else {
      return false;
    }
  }
  while (p < pattern.size() && pattern[p] == '*') ++p;
  return p == pattern.size();
}

class GateConfigReader {
 public:
  explicit GateConfigReader(const std::string& source) : s_(source) {
    self_ = fs::absolute(fs::path(source)).lexically_normal();
    base_ = self_.parent_path();
  }

  GateConfig read(const json& root) const {
    GateConfig cfg;
    cfg.source = s_.source();
    s_.require_object(root, "");
    s_.check_fields(root, "", {"corpus", "stress"});
    const json* corpus_section = s_.optional(root, "corpus");
    const json* stress_section = s_.optional(root, "stress");
    if (corpus_section == nullptr && stress_section == nullptr)
      s_.fail("", "needs a \"corpus\" or a \"stress\" section (or both)");
    if (corpus_section != nullptr) corpus(*corpus_section, "corpus", cfg);
    if (stress_section != nullptr) stress(*stress_section, "stress", cfg);
    // The corpus is read last, so that every problem of the config itself is reported first.
    for (const auto& f : cfg.case_files) cfg.cases.push_back(read_case_file(f));
    return cfg;
  }

 private:
  // stress.count: a JSON integer >= 1 (1.0 is refused).
  long positive_integer(const json& j, const std::string& path) const {
    if (!j.is_number_integer() || j.get<long long>() < 1)
      s_.fail(path, "must be an integer >= 1, got " + j.dump());
    return static_cast<long>(j.get<long long>());
  }

  // A limit: a finite number >= 0 (the message shows the value as written, strings quoted).
  double limit_value(const json& j, const std::string& path) const {
    if (!j.is_number() || !std::isfinite(j.get<double>()) || j.get<double>() < 0)
      s_.fail(path, "must be a finite number >= 0, got " + j.dump());
    return j.get<double>();
  }

  // Case files matching `pattern` (a path whose last component may hold * and ?), sorted;
  // the config file itself is never a case.
  std::vector<std::string> expand(const std::string& pattern, const std::string& path) const {
    fs::path p(pattern);
    if (p.is_relative()) p = base_ / p;
    p = p.lexically_normal();
    const std::string name = p.filename().string();
    std::vector<std::string> out;
    if (name.find_first_of("*?") == std::string::npos) {
      if (!fs::is_regular_file(p)) s_.fail(path, "no such case file: " + p.string());
      out.push_back(p.string());
      return out;
    }
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(p.parent_path(), ec))
      if (entry.is_regular_file() && glob_match(name, entry.path().filename().string()) &&
          entry.path().lexically_normal() != self_)
        out.push_back(entry.path().lexically_normal().string());
    if (ec) s_.fail(path, "cannot list " + p.parent_path().string() + " (" + ec.message() + ")");
    if (out.empty()) s_.fail(path, "no file matches " + p.string());
    std::sort(out.begin(), out.end());
    return out;
  }

  // One limit set: {"<metric>": limit, ..., "<only_key>": [names]}.
  GateMethod limit_set(const MethodSpec& spec, const json& j, const std::string& path,
                       const std::string& only_key,
                       const std::vector<std::string>& known_names) const {
    std::vector<std::string> allowed = gate_metrics();
    allowed.push_back(only_key);
    s_.require_object(j, path);
    s_.check_fields(j, path, allowed);
    GateMethod gm;
    gm.spec = spec;
    for (const auto& limit : j.items()) {
      const std::string lpath = member_path(path, limit.key());
      if (limit.key() == only_key) {
        gm.only = s_.non_empty_strings(limit.value(), lpath);
        for (std::size_t i = 0; i < gm.only.size(); ++i)
          if (std::find(known_names.begin(), known_names.end(), gm.only[i]) == known_names.end())
            s_.fail(index_path(lpath, i),
                    "'" + gm.only[i] + "' is not one of the " + only_key + " run here");
        continue;
      }
      gm.limits[limit.key()] = limit_value(limit.value(), lpath);
    }
    if (gm.limits.empty()) s_.fail(path, "sets no limit");
    return gm;
  }

  // {"<method spec>": <limit set> or [<limit set>, ...], ...}; several sets let one method
  // have different limits on different cases or regimes.
  std::vector<GateMethod> methods(const json& j, const std::string& path, const std::string& only_key,
                                  const std::vector<std::string>& known_names) const {
    s_.require_object(j, path);
    if (j.empty()) s_.fail(path, "must name at least one method");
    std::vector<GateMethod> out;
    for (const auto& item : j.items()) {
      const std::string mpath = member_path(path, item.key());
      MethodSpec spec;
      try {
        spec = parse_method_spec(item.key());  // type and range of every value: the method table
      } catch (const MethodSpecError& e) {
        // The message starts with the spec, which mpath names already.
        std::string why = e.what();
        if (why.compare(0, item.key().size() + 2, item.key() + ": ") == 0)
          why.erase(0, item.key().size() + 2);
        s_.fail(mpath, why);
      }
      const json& v = item.value();
      if (v.is_array()) {
        if (v.empty()) s_.fail(mpath, "must be a limit set or a non-empty array of them, got []");
        for (std::size_t i = 0; i < v.size(); ++i)
          out.push_back(limit_set(spec, v[i], index_path(mpath, i), only_key, known_names));
      } else {
        out.push_back(limit_set(spec, v, mpath, only_key, known_names));
      }
    }
    return out;
  }

  void corpus(const json& j, const std::string& path, GateConfig& cfg) const {
    s_.require_object(j, path);
    s_.check_fields(j, path, {"cases", "methods"});
    const std::string cpath = member_path(path, "cases");
    const std::vector<std::string> patterns = s_.non_empty_strings(s_.required(j, path, "cases"), cpath);
    for (std::size_t i = 0; i < patterns.size(); ++i)
      for (auto& f : expand(patterns[i], index_path(cpath, i)))
        if (std::find(cfg.case_files.begin(), cfg.case_files.end(), f) == cfg.case_files.end())
          cfg.case_files.push_back(f);
    // Case names are file names without .json (the corpus convention, checked by its tests).
    std::vector<std::string> names;
    for (const auto& f : cfg.case_files) names.push_back(fs::path(f).stem().string());
    cfg.corpus_methods =
        methods(s_.required(j, path, "methods"), member_path(path, "methods"), "cases", names);
  }

  void stress(const json& j, const std::string& path, GateConfig& cfg) const {
    s_.require_object(j, path);
    s_.check_fields(j, path, {"count", "seed", "regimes", "methods"});
    cfg.stress = true;
    cfg.stress_count = positive_integer(s_.required(j, path, "count"), member_path(path, "count"));
    limits::check(limits::kStressSamples, static_cast<double>(cfg.stress_count),
                  s_.source() + ": " + member_path(path, "count"));
    const json& seed = s_.required(j, path, "seed");
    if (!seed.is_number_unsigned())
      s_.fail(member_path(path, "seed"), "must be an integer >= 0, got " + seed.dump());
    cfg.stress_seed = seed.get<std::uint64_t>();
    std::vector<std::string> names;
    if (const json* regimes = s_.optional(j, "regimes")) {
      const std::string rpath = member_path(path, "regimes");
      const std::vector<std::string> list = s_.non_empty_strings(*regimes, rpath);
      for (std::size_t i = 0; i < list.size(); ++i) {
        Regime r;
        if (!parse_regime(list[i], r)) s_.fail(index_path(rpath, i), "unknown regime '" + list[i] + "'");
        cfg.stress_regimes.push_back(r);
        names.push_back(list[i]);
      }
    } else {
      for (const Regime r : stress_regimes()) names.push_back(regime_name(r));
    }
    cfg.stress_methods =
        methods(s_.required(j, path, "methods"), member_path(path, "methods"), "regimes", names);
  }

  OrderedJsonSchema s_;
  fs::path self_;
  fs::path base_;
};

}  // namespace

GateConfig parse_gate_config_text(std::string_view text, const std::string& source) {
  // Duplicate keys are errors (json_source): a gate whose limit was overridden by a later
  // duplicate would check something else than it says.
  return GateConfigReader(source).read(json_source::parse_ordered(text, source));
}

GateConfig read_gate_config(const std::string& path) {
  return parse_gate_config_text(json_source::read_text_file(path), path);
}

}  // namespace rayint
