// registry.cpp -- method specs ("name:key=value") and the table of known methods.
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include "rayint/integrators/exact.hpp"
#include "rayint/integrators/factories.hpp"
#include "rayint/integrators/integrator.hpp"
#include "rayint/integrators/paper.hpp"

namespace rayint {
namespace {

struct MethodEntry {
  const char* name;
  const char* params;  // accepted parameter names, space-separated
  std::unique_ptr<RayIntegrator> (*make)(const MethodSpec&, const TransferFunctions&);
};

std::vector<MethodEntry>& registry() {
  static std::vector<MethodEntry> entries = {
      // path=batch (default): exact_batch, vectorised; path=scalar: exact_piece per piece-channel.
      {"exact", "path",
       [](const MethodSpec& spec, const TransferFunctions& tf) -> std::unique_ptr<RayIntegrator> {
         const std::string path = spec.text("path", "batch");
         if (path != "batch" && path != "scalar")
           throw std::invalid_argument("exact: path must be batch or scalar, not '" + path + "'");
         return std::make_unique<ExactIntegrator>(
             tf, path == "scalar" ? ExactIntegrator::Path::scalar : ExactIntegrator::Path::batch);
       }},
      {"paper", "",
       [](const MethodSpec&, const TransferFunctions& tf) -> std::unique_ptr<RayIntegrator> {
         return std::make_unique<PaperIntegrator>(tf);
       }},
      // One line per method; the accepted parameters are the method's accuracy knobs.
      {"ode", "rtol atol", make_ode},
      {"rk4", "n", make_rk4},
      {"riemann", "n dt order correction ref_dt", make_riemann},
      {"eq5", "", make_eq5},
      {"eq6", "", make_eq6},
      {"eq7", "", make_eq7},
      {"eq8", "", make_eq8},
      {"particle", "", make_particle},
      {"preintegrated", "size lookup dims step max_length lengths", make_preintegrated},
      {"psi_table", "size lookup", make_psi_table},
      {"nerf", "n at last", make_nerf},
      {"pl_nerf", "n color", make_pl_nerf},
  };
  return entries;
}

const MethodEntry& find_entry(const std::string& name) {
  for (const auto& e : registry())
    if (name == e.name) return e;
  std::string known;
  for (const auto& e : registry()) known += std::string(known.empty() ? "" : ", ") + e.name;
  throw std::invalid_argument("unknown method '" + name + "' (known: " + known + ")");
}

}  // namespace

void register_method(const char* name, const char* params, MethodFactory make) {
  for (const auto& e : registry())
    if (std::string(name) == e.name)
      throw std::invalid_argument(std::string("method '") + name + "' is already registered");
  registry().push_back({name, params, make});
}

std::string MethodSpec::label() const {
  std::string out = name;
  for (const auto& [k, v] : params) out += ":" + k + "=" + v;
  return out;
}

double MethodSpec::number(const std::string& key, double fallback) const {
  const auto it = params.find(key);
  if (it == params.end()) return fallback;
  char* end = nullptr;
  const double v = std::strtod(it->second.c_str(), &end);
  if (end == it->second.c_str() || *end != '\0' || !std::isfinite(v))
    throw std::invalid_argument("method " + name + ": parameter " + key +
                                " must be a number, got '" + it->second + "'");
  return v;
}

std::string MethodSpec::text(const std::string& key, const std::string& fallback) const {
  const auto it = params.find(key);
  return it == params.end() ? fallback : it->second;
}

MethodSpec parse_method_spec(const std::string& text) {
  MethodSpec spec;
  std::stringstream in(text);
  std::string part;
  std::getline(in, spec.name, ':');
  if (spec.name.empty()) throw std::invalid_argument("empty method name in '" + text + "'");
  const MethodEntry& entry = find_entry(spec.name);
  const std::string allowed = std::string(" ") + entry.params + " ";
  while (std::getline(in, part, ':')) {
    const auto eq = part.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == part.size())
      throw std::invalid_argument("method " + spec.name + ": expected key=value, got '" + part + "'");
    const std::string key = part.substr(0, eq);
    if (allowed.find(" " + key + " ") == std::string::npos)
      throw std::invalid_argument("method " + spec.name + ": unknown parameter '" + key +
                                  "' (accepted:" + (entry.params[0] ? " " : " none") +
                                  entry.params + ")");
    spec.params[key] = part.substr(eq + 1);
  }
  return spec;
}

std::vector<MethodSpec> parse_method_list(const std::string& csv) {
  std::vector<MethodSpec> out;
  std::stringstream in(csv);
  std::string item;
  while (std::getline(in, item, ','))
    if (!item.empty()) out.push_back(parse_method_spec(item));
  if (out.empty()) throw std::invalid_argument("no methods given");
  return out;
}

std::unique_ptr<RayIntegrator> make_integrator(const MethodSpec& spec,
                                               const TransferFunctions& tf) {
  return find_entry(spec.name).make(spec, tf);
}

std::vector<std::string> method_names() {
  std::vector<std::string> out;
  for (const auto& e : registry()) out.emplace_back(e.name);
  return out;
}

std::vector<MethodSpec> default_methods() { return parse_method_list("exact,paper"); }

}  // namespace rayint
