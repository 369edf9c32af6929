// Reading and validating a gate config (format: docs/gates.md). A strict walk over the JSON:
// no duplicate keys, known fields only, required fields present, limits finite and >= 0,
// methods that parse and can be built, regimes that exist, case patterns that match files, and
// case names that are in the corpus.
#include "rayint/input/gate_config.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <set>
#include <vector>
#include <sstream>

#include "rayint/input/case_reader.hpp"

namespace rayint {
namespace {

using json = nlohmann::ordered_json;  // keeps the config's order: checks are reported in it
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

class GateSchema {
 public:
  explicit GateSchema(const std::string& source) : source_(source) {
    self_ = fs::absolute(fs::path(source)).lexically_normal();
    base_ = self_.parent_path();
  }

  GateConfig read(const json& root) const {
    GateConfig cfg;
    cfg.source = source_;
    require_object(root, "");
    check_fields(root, "", {"corpus", "stress"});
    if (!root.contains("corpus") && !root.contains("stress"))
      fail("", "needs a \"corpus\" or a \"stress\" section (or both)");
    if (root.contains("corpus")) corpus(root.at("corpus"), "corpus", cfg);
    if (root.contains("stress")) stress(root.at("stress"), "stress", cfg);
    // The corpus is read last, so that every problem of the config itself is reported first.
    for (const auto& f : cfg.case_files) cfg.cases.push_back(read_case_file(f));
    return cfg;
  }

 private:
  [[noreturn]] void fail(const std::string& path, const std::string& what) const {
    throw InputError(source_ + ": " + (path.empty() ? "(root)" : path) + ": " + what);
  }

  static std::string member(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }
  static std::string index(const std::string& path, std::size_t i) {
    return path + "[" + std::to_string(i) + "]";
  }

  void require_object(const json& j, const std::string& path) const {
    if (!j.is_object()) fail(path, std::string("must be an object, got ") + j.type_name());
  }

  void check_fields(const json& j, const std::string& path,
                    const std::vector<std::string>& allowed) const {
    for (const auto& item : j.items())
      if (std::find(allowed.begin(), allowed.end(), item.key()) == allowed.end()) {
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        fail(member(path, item.key()), "unknown field (expected " + list + ")");
      }
  }

  const json& required(const json& j, const std::string& path, const std::string& key) const {
    if (!j.contains(key)) fail(member(path, key), "missing required field");
    return j.at(key);
  }

  std::vector<std::string> strings(const json& j, const std::string& path) const {
    if (!j.is_array() || j.empty())
      fail(path, std::string("must be a non-empty array of strings, got ") +
                     (j.is_array() ? "[]" : j.type_name()));
    std::vector<std::string> out;
    for (std::size_t i = 0; i < j.size(); ++i) {
      if (!j[i].is_string() || j[i].get_ref<const std::string&>().empty())
        fail(index(path, i), std::string("must be a non-empty string, got ") + j[i].type_name());
      out.push_back(j[i].get<std::string>());
    }
    return out;
  }

  long positive_integer(const json& j, const std::string& path) const {
    if (!j.is_number_integer() || j.get<long long>() < 1)
      fail(path, "must be an integer >= 1, got " + j.dump());
    return static_cast<long>(j.get<long long>());
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
      if (!fs::is_regular_file(p)) fail(path, "no such case file: " + p.string());
      out.push_back(p.string());
      return out;
    }
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(p.parent_path(), ec))
      if (entry.is_regular_file() && glob_match(name, entry.path().filename().string()) &&
          entry.path().lexically_normal() != self_)
        out.push_back(entry.path().lexically_normal().string());
    if (ec) fail(path, "cannot list " + p.parent_path().string() + " (" + ec.message() + ")");
    if (out.empty()) fail(path, "no file matches " + p.string());
    std::sort(out.begin(), out.end());
    return out;
  }

  // One limit set: {"<metric>": limit, ..., "<only_key>": [names]}.
  GateMethod limit_set(const MethodSpec& spec, const json& j, const std::string& path,
                       const std::string& only_key,
                       const std::vector<std::string>& known_names) const {
    std::vector<std::string> allowed = gate_metrics();
    allowed.push_back(only_key);
    require_object(j, path);
    check_fields(j, path, allowed);
    GateMethod gm;
    gm.spec = spec;
    for (const auto& limit : j.items()) {
      const std::string lpath = member(path, limit.key());
      if (limit.key() == only_key) {
        gm.only = strings(limit.value(), lpath);
        for (std::size_t i = 0; i < gm.only.size(); ++i)
          if (std::find(known_names.begin(), known_names.end(), gm.only[i]) == known_names.end())
            fail(index(lpath, i), "'" + gm.only[i] + "' is not one of the " + only_key + " run here");
        continue;
      }
      const json& v = limit.value();
      if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < 0)
        fail(lpath, "must be a finite number >= 0, got " + v.dump());
      gm.limits[limit.key()] = v.get<double>();
    }
    if (gm.limits.empty()) fail(path, "sets no limit");
    return gm;
  }

  // {"<method spec>": <limit set> or [<limit set>, ...], ...}; several sets let one method
  // have different limits on different cases or regimes.
  std::vector<GateMethod> methods(const json& j, const std::string& path, const std::string& only_key,
                                  const std::vector<std::string>& known_names) const {
    require_object(j, path);
    if (j.empty()) fail(path, "must name at least one method");
    std::vector<GateMethod> out;
    for (const auto& item : j.items()) {
      const std::string mpath = member(path, item.key());
      MethodSpec spec;
      try {
        spec = parse_method_spec(item.key());
        make_integrator(spec, probe_);  // parameter values are checked when a method is built
      } catch (const std::invalid_argument& e) {
        fail(mpath, e.what());
      }
      const json& v = item.value();
      if (v.is_array()) {
        if (v.empty()) fail(mpath, "must be a limit set or a non-empty array of them, got []");
        for (std::size_t i = 0; i < v.size(); ++i)
          out.push_back(limit_set(spec, v[i], index(mpath, i), only_key, known_names));
      } else {
        out.push_back(limit_set(spec, v, mpath, only_key, known_names));
      }
    }
    return out;
  }

  void corpus(const json& j, const std::string& path, GateConfig& cfg) const {
    require_object(j, path);
    check_fields(j, path, {"cases", "methods"});
    const std::string cpath = member(path, "cases");
    const std::vector<std::string> patterns = strings(required(j, path, "cases"), cpath);
    for (std::size_t i = 0; i < patterns.size(); ++i)
      for (auto& f : expand(patterns[i], index(cpath, i)))
        if (std::find(cfg.case_files.begin(), cfg.case_files.end(), f) == cfg.case_files.end())
          cfg.case_files.push_back(f);
    // Case names are file names without .json (the corpus convention, checked by its tests).
    std::vector<std::string> names;
    for (const auto& f : cfg.case_files) names.push_back(fs::path(f).stem().string());
    cfg.corpus_methods = methods(required(j, path, "methods"), member(path, "methods"), "cases", names);
  }

  void stress(const json& j, const std::string& path, GateConfig& cfg) const {
    require_object(j, path);
    check_fields(j, path, {"count", "seed", "regimes", "methods"});
    cfg.stress = true;
    cfg.stress_count = positive_integer(required(j, path, "count"), member(path, "count"));
    const json& seed = required(j, path, "seed");
    if (!seed.is_number_unsigned()) fail(member(path, "seed"), "must be an integer >= 0, got " + seed.dump());
    cfg.stress_seed = seed.get<std::uint64_t>();
    std::vector<std::string> names;
    if (j.contains("regimes")) {
      const std::string rpath = member(path, "regimes");
      const std::vector<std::string> list = strings(j.at("regimes"), rpath);
      for (std::size_t i = 0; i < list.size(); ++i) {
        Regime r;
        if (!parse_regime(list[i], r)) fail(index(rpath, i), "unknown regime '" + list[i] + "'");
        cfg.stress_regimes.push_back(r);
        names.push_back(list[i]);
      }
    } else {
      for (const Regime r : stress_regimes()) names.push_back(regime_name(r));
    }
    cfg.stress_methods = methods(required(j, path, "methods"), member(path, "methods"), "regimes", names);
  }

  // A small valid transfer-function set on which every method must build (linear density,
  // constant colour, shared by the channels, as even the particle model accepts).
  static TransferFunctions probe_transfer() {
    TransferFunctions tf;
    for (int c = 0; c < kChannels; ++c) {
      tf.density[c] = {{0.0, 1.0}, {1.0, 2.0}};
      tf.color[c] = {{0.0}, {1.0}};
    }
    return tf;
  }

  std::string source_;
  fs::path self_;
  fs::path base_;
  TransferFunctions probe_ = probe_transfer();
};

}  // namespace

GateConfig parse_gate_config_text(std::string_view text, const std::string& source) {
  // The DOM parser silently keeps the last of two equal keys; a gate whose limit was overridden
  // by a later duplicate would check something else than it says, so duplicates are errors.
  struct Frame {
    bool object;
    std::string path;
    std::set<std::string> keys;
    std::string key;  // last key seen (objects)
    long next = 0;    // next index (arrays)
  };
  std::vector<Frame> stack;
  std::string duplicate;  // field path of the first duplicate key
  auto child = [&stack]() -> std::string {
    if (stack.empty()) return "";
    Frame& f = stack.back();
    if (f.object) return f.path.empty() ? f.key : f.path + "." + f.key;
    return f.path + "[" + std::to_string(f.next++) + "]";
  };
  const json::parser_callback_t callback = [&](int, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
        stack.push_back({true, child(), {}, {}, 0});
        break;
      case json::parse_event_t::array_start:
        stack.push_back({false, child(), {}, {}, 0});
        break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        if (!stack.empty()) stack.pop_back();
        break;
      case json::parse_event_t::key:
        if (!stack.empty() && parsed.is_string()) {
          Frame& f = stack.back();
          f.key = parsed.get<std::string>();
          if (!f.keys.insert(f.key).second && duplicate.empty())
            duplicate = f.path.empty() ? f.key : f.path + "." + f.key;
        }
        break;
      case json::parse_event_t::value:
        if (!stack.empty() && !stack.back().object) child();
        break;
    }
    return true;
  };
  json root;
  try {
    root = json::parse(text.begin(), text.end(), callback);
  } catch (const json::exception& e) {
    std::string what = e.what();
    const auto bracket = what.find("] ");
    if (bracket != std::string::npos) what = what.substr(bracket + 2);
    throw InputError(source + ": (root): invalid JSON: " + what);
  }
  if (!duplicate.empty()) throw InputError(source + ": " + duplicate + ": duplicate field");
  return GateSchema(source).read(root);
}

GateConfig read_gate_config(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot read file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(path + ": cannot read file");
  return parse_gate_config_text(text.str(), path);
}

}  // namespace rayint
