// registry.cpp -- method specs ("name:key=value") and the one table of known methods: each
// method's parameters with type, default, range and a line of text. parse_method_spec checks a
// spec against it before anything runs; the factories read their values and defaults from it
// (MethodSpec::number/integer/text), so the validator and the factories cannot disagree;
// `rayint methods` prints it.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "rayint/integrators/exact.hpp"
#include "rayint/integrators/factories.hpp"
#include "rayint/integrators/integrator.hpp"
#include "rayint/integrators/paper.hpp"
#include "rayint/integrators/preintegrated.hpp"
#include "rayint/integrators/riemann.hpp"

namespace rayint {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The largest count parameter (samples, intervals, steps per segment): 1e9 keeps the count an
// int with room to spare; a run at that count would take hours per ray, so no real setting is cut.
constexpr double kMaxCount = 1e9;

std::vector<MethodSchema>& registry() {
  static std::vector<MethodSchema> entries = {
      {"exact",
       "closed form of the ray integral per piece (rho, kappa linear), the method under test",
       {choice_param("path", "batch", {"batch", "scalar"},
                     "batch: vectorised over pieces (exact_batch); scalar: one piece-channel at a time")},
       [](const MethodSpec& spec, const TransferFunctions& tf) -> std::unique_ptr<RayIntegrator> {
         return std::make_unique<ExactIntegrator>(
             tf, spec.text("path") == "scalar" ? ExactIntegrator::Path::scalar
                                               : ExactIntegrator::Path::batch);
       },
       nullptr},
      {"paper",
       "the closed form of Williams & Max 1992 Sec. 3.3 as printed (complex Erfi)",
       {},
       [](const MethodSpec&, const TransferFunctions& tf) -> std::unique_ptr<RayIntegrator> {
         return std::make_unique<PaperIntegrator>(tf);
       },
       nullptr},
      {"ode",
       "adaptive Dormand-Prince 5(4) on Eq. 3 (Boost.Odeint), per piece",
       {number_param("rtol", "1e-8", 1e-15, false, 1.0, true,
                     "relative tolerance per step (below 1e-15 the error estimate is rounding "
                     "noise and the step collapses)"),
        number_param("atol", "2.2250738585072014e-308", 0.0, true, kInf, false,
                     "absolute tolerance per step (default DBL_MIN: control is relative; 0 would "
                     "make the error ratio 0/0 where I = 0 and rho = 0)")},
       make_ode, nullptr},
      {"rk4",
       "classical Runge-Kutta on Eq. 3, n equal steps per piece",
       {integer_param("n", "16", 1, kMaxCount, "steps per piece")},
       make_rk4, nullptr},
      {"riemann",
       "Riemann sum with per-sample opacity (the ray caster's loop), n samples per segment or a step dt",
       {integer_param("n", "64", 1, kMaxCount, "samples per segment (not with dt)"),
        number_param("dt", "", 0.0, true, kInf, false,
                     "fixed step along the whole ray instead of n per segment"),
        choice_param("order", "btf", {"btf", "ftb"}, "compositing order: back to front or front to back"),
        choice_param("correction", "exp", {"exp", "none", "linear"},
                     "opacity per step: exact 1-e^-x, as tabulated for ref_dt, or linear x"),
        number_param("ref_dt", "", 0.0, true, kInf, false,
                     "step the opacity table was made for (correction exp: corrected; none: required)")},
       make_riemann, [](const MethodSpec& spec) { riemann_options(spec); }},
      {"eq5", "Williams & Max Eq. 5: kappa frozen at its average per piece, int rho exact", {},
       make_cell_rule<CellRule::eq5>, nullptr},
      {"eq6", "Williams & Max Eq. 6: kappa and rho averaged from each cell's end values", {},
       make_cell_rule<CellRule::eq6>, nullptr},
      {"eq7", "Williams & Max Eq. 7: Eq. 6 stored as one opacity per cell", {},
       make_cell_rule<CellRule::eq7>, nullptr},
      {"eq8", "Williams & Max Eq. 8: opacity rho L (clamped to 1), for thin cells", {},
       make_cell_rule<CellRule::eq8>, nullptr},
      {"particle",
       "Sabella's particle model (Williams & Max Sec. 2, Eq. 2); needs one density for all "
       "channels and constant colours",
       {}, make_particle, nullptr},
      {"preintegrated",
       "pre-integrated transfer functions (Engel et al. 2001; dims=3 after Roettger et al. 2000)",
       {integer_param("size", "256", 2, 4729, "scalar grid points per axis",
                      "a dims=2 table takes 48 B per entry: 1 GiB at 4729"),
        choice_param("lookup", "linear", {"nearest", "linear"}, "table lookup"),
        integer_param("dims", "2", 2, 3, "2: fixed step; 3: segment length as a third axis"),
        number_param("step", "0.015625", 0.0, true, kInf, false, "dims=2: the sampling distance"),
        number_param("max_length", "4", 0.0, true, kInf, false,
                     "dims=3: longest length on the length axis"),
        integer_param("lengths", "", 2, 4096, "dims=3: planes on the length axis (default min(size, 32))")},
       make_preintegrated, [](const MethodSpec& spec) { preintegrated_options(spec); }},
      {"psi_table",
       "partial pre-integration (Moreland & Angel 2004): a table of Psi, the rest exact",
       {integer_param("size", "512", 2, 8192, "table points per axis",
                      "the table takes 16 B per entry: 1 GiB at 8192"),
        choice_param("lookup", "linear", {"nearest", "linear", "floor"},
                     "table lookup (floor: VTK's Psi())")},
       make_psi_table, nullptr},
      {"nerf",
       "NeRF quadrature (Mildenhall et al. 2020): n intervals per segment, constant sigma and colour",
       {integer_param("n", "64", 1, kMaxCount, "intervals per segment"),
        choice_param("at", "mid", {"mid", "near"}, "where each interval is sampled"),
        choice_param("last", "interval", {"interval", "inf"},
                     "the last interval's length (inf: NeRF's 1e10)")},
       make_nerf, nullptr},
      {"pl_nerf",
       "piecewise-linear NeRF quadrature: sigma linear per interval",
       {integer_param("n", "64", 1, kMaxCount, "intervals per segment"),
        choice_param("color", "mid", {"mid", "near"}, "colour per interval")},
       make_pl_nerf, nullptr},
  };
  return entries;
}

const MethodSchema* find_info(const std::string& name) {
  for (const auto& e : registry())
    if (name == e.name) return &e;
  return nullptr;
}

const MethodParam* find_param(const MethodSchema& info, const std::string& key) {
  for (const auto& p : info.params)
    if (p.name == key) return &p;
  return nullptr;
}

// `text` for a one-line message: control bytes and bytes >= 0x7f as \xNN.
std::string printable(const std::string& text) {
  std::string out;
  for (const char ch : text) {
    const auto b = static_cast<unsigned char>(ch);
    if (b >= 0x20 && b < 0x7f) {
      out += ch;
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", b);
      out += buf;
    }
  }
  return out;
}

// A bound in a message: integers plainly, large or small ones as 1e9, 1e-15.
std::string bound_text(double x) {
  if (x == std::floor(x) && std::fabs(x) < 1e6) return std::to_string(static_cast<long long>(x));
  char buf[64];
  std::snprintf(buf, sizeof buf, "%g", x);
  std::string s = buf;
  const auto e = s.find('e');
  if (e != std::string::npos) {  // 1e+09 -> 1e9, 1e-08 -> 1e-8
    std::string exponent = s.substr(e + 1);
    const bool negative = exponent[0] == '-';
    if (exponent[0] == '+' || exponent[0] == '-') exponent.erase(0, 1);
    while (exponent.size() > 1 && exponent[0] == '0') exponent.erase(0, 1);
    s = s.substr(0, e) + "e" + (negative ? "-" : "") + exponent;
  }
  return s;
}

// A number as people type it: 64, 1e3, 0.5, -2. Not hex, not inf or nan, nothing after it.
bool read_number(const std::string& text, double& out) {
  if (text.empty() || text.find_first_of("xXpP") != std::string::npos) return false;
  const char* begin = text.c_str();
  char* end = nullptr;
  out = std::strtod(begin, &end);
  return end != begin && *end == '\0' && std::isfinite(out) &&
         text.find_first_of(" \t\n") == std::string::npos;
}

// Why `value` is not allowed for `p`, or "" if it is.
std::string value_problem(const MethodParam& p, const std::string& value) {
  if (p.type == MethodParam::Type::choice) {
    for (const auto& c : p.choices)
      if (value == c) return "";
    return p.name + " must be " + allowed_values(p);
  }
  double v = 0.0;
  const bool integer = p.type == MethodParam::Type::integer;
  if (!read_number(value, v) || (integer && v != std::floor(v)))
    return p.name + " must be " + allowed_values(p);
  const std::string kind = integer ? "an integer " : "a number ";
  if (p.has_min && (p.min_exclusive ? !(v > p.min) : !(v >= p.min)))
    return p.name + " must be " + kind + (p.min_exclusive ? "> " : ">= ") + bound_text(p.min);
  if (p.has_max && (p.max_exclusive ? !(v < p.max) : !(v <= p.max)))
    return p.name + " must be " + kind + (p.max_exclusive ? "< " : "<= ") + bound_text(p.max) +
           (p.limit.empty() ? "" : " (" + p.limit + ")");
  return "";
}

// The parameter `key` of the registered method of `spec`, for the typed getters.
const MethodParam& param_of(const MethodSpec& spec, const std::string& key) {
  const MethodSchema* info = find_info(spec.name);
  const MethodParam* p = info ? find_param(*info, key) : nullptr;
  if (!p) throw std::logic_error("method " + spec.name + " has no parameter '" + key + "' in its table");
  return *p;
}

// The value of `key` as text: given, else the table's default (which must exist).
std::string value_of(const MethodSpec& spec, const MethodParam& p) {
  const auto it = spec.params.find(p.name);
  if (it != spec.params.end()) return it->second;
  if (p.fallback.empty())
    throw std::logic_error("method " + spec.name + ": parameter " + p.name + " has no default");
  return p.fallback;
}

}  // namespace

const char* type_name(MethodParam::Type t) {
  switch (t) {
    case MethodParam::Type::integer: return "integer";
    case MethodParam::Type::number: return "number";
    case MethodParam::Type::choice: return "choice";
  }
  return "?";
}

std::string allowed_values(const MethodParam& p) {
  if (p.type == MethodParam::Type::choice) {
    std::string out;
    for (std::size_t i = 0; i < p.choices.size(); ++i)
      out += (i == 0 ? "" : i + 1 == p.choices.size() ? " or " : ", ") + p.choices[i];
    return out;
  }
  const std::string kind = p.type == MethodParam::Type::integer ? "an integer" : "a number";
  if (p.has_min && p.has_max)
    return kind + " in " + (p.min_exclusive ? "(" : "[") + bound_text(p.min) + ", " +
           bound_text(p.max) + (p.max_exclusive ? ")" : "]");
  if (p.has_min) return kind + (p.min_exclusive ? " > " : " >= ") + bound_text(p.min);
  if (p.has_max) return kind + (p.max_exclusive ? " < " : " <= ") + bound_text(p.max);
  return kind;
}

MethodParam integer_param(const std::string& name, const std::string& fallback, double min,
                          double max, const std::string& about, const std::string& limit) {
  // A number in [min, max] of integer type: its range is always closed, also for a max of inf.
  MethodParam p = number_param(name, fallback, min, false, max, false, about, limit);
  p.type = MethodParam::Type::integer;
  p.has_max = true;
  return p;
}

MethodParam number_param(const std::string& name, const std::string& fallback, double min,
                         bool min_exclusive, double max, bool max_exclusive,
                         const std::string& about, const std::string& limit) {
  MethodParam p;
  p.name = name;
  p.type = MethodParam::Type::number;
  p.fallback = fallback;
  p.min = min;
  p.min_exclusive = min_exclusive;
  p.has_min = true;
  p.max = max;
  p.max_exclusive = max_exclusive;
  p.has_max = std::isfinite(max);
  p.about = about;
  p.limit = limit;
  return p;
}

MethodParam choice_param(const std::string& name, const std::string& fallback,
                         std::vector<std::string> choices, const std::string& about) {
  MethodParam p;
  p.name = name;
  p.type = MethodParam::Type::choice;
  p.fallback = fallback;
  p.choices = std::move(choices);
  p.about = about;
  return p;
}

void register_method(MethodSchema info) {
  if (find_info(info.name))
    throw std::invalid_argument("method '" + info.name + "' is already registered");
  registry().push_back(std::move(info));
}

const std::vector<MethodSchema>& method_table() { return registry(); }

const MethodSchema& method_schema(const std::string& name) {
  if (const MethodSchema* info = find_info(name)) return *info;
  std::string known;
  for (const auto& e : registry()) known += (known.empty() ? "" : ", ") + e.name;
  throw MethodSpecError(printable(name) + ": unknown method (known: " + known + ")");
}

std::string MethodSpec::label() const { return spelling.empty() ? canonical() : spelling; }

std::string MethodSpec::canonical() const {
  std::string out = name;
  for (const auto& [k, v] : params) out += ":" + k + "=" + v;
  return out;
}

double MethodSpec::number(const std::string& key) const {
  const MethodParam& p = param_of(*this, key);
  double v = 0.0;
  if (!read_number(value_of(*this, p), v))
    throw std::logic_error("method " + name + ": " + key + " is not a number (spec not validated?)");
  return v;
}

int MethodSpec::integer(const std::string& key) const {
  const double v = number(key);
  if (v != std::floor(v) || std::fabs(v) > std::numeric_limits<int>::max())
    throw std::logic_error("method " + name + ": " + key + " is not an int (spec not validated?)");
  return static_cast<int>(v);
}

std::string MethodSpec::text(const std::string& key) const {
  return value_of(*this, param_of(*this, key));
}

std::size_t choice_of(const MethodSpec& spec, const std::string& key, std::initializer_list<const char*> values) {
  const std::string value = spec.text(key);
  std::string listed;
  std::size_t i = 0;
  for (const char* v : values) {
    if (value == v) return i;
    listed += std::string(i == 0 ? "" : i + 1 == values.size() ? " or " : ", ") + v;
    ++i;
  }
  throw std::invalid_argument("method " + spec.name + ": " + key + " must be " + listed + ", got '" + value + "'");
}

double MethodSpec::number(const std::string& key, double fallback) const {
  const auto it = params.find(key);
  if (it == params.end()) return fallback;
  double v = 0.0;
  if (!read_number(it->second, v))
    throw std::invalid_argument("method " + name + ": parameter " + key +
                                " must be a number, got '" + it->second + "'");
  return v;
}

std::string MethodSpec::text(const std::string& key, const std::string& fallback) const {
  const auto it = params.find(key);
  return it == params.end() ? fallback : it->second;
}

MethodSpec parse_method_spec(const std::string& typed) {
  // Messages start with the spec as typed (control bytes escaped, so they stay one line).
  const std::string text = printable(typed);
  MethodSpec spec;
  spec.spelling = typed;
  std::stringstream in(typed);
  std::string part;
  std::getline(in, spec.name, ':');
  if (spec.name.empty()) throw MethodSpecError(text + ": empty method name");
  const MethodSchema* info = find_info(spec.name);
  if (!info) {
    std::string known;
    for (const auto& e : registry()) known += (known.empty() ? "" : ", ") + e.name;
    throw MethodSpecError(text + ": unknown method '" + printable(spec.name) + "' (known: " + known + ")");
  }
  while (std::getline(in, part, ':')) {
    const auto eq = part.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == part.size())
      throw MethodSpecError(text + ": expected key=value, got '" + printable(part) + "'");
    const std::string key = part.substr(0, eq);
    const MethodParam* p = find_param(*info, key);
    if (!p) {
      std::string accepted;
      for (const auto& q : info->params) accepted += (accepted.empty() ? "" : ", ") + q.name;
      throw MethodSpecError(text + ": unknown parameter '" + printable(key) + "' (" + spec.name + " takes " +
                            (accepted.empty() ? std::string("no parameters") : accepted) + ")");
    }
    if (spec.params.count(key)) throw MethodSpecError(text + ": " + key + " given twice");
    const std::string value = part.substr(eq + 1);
    const std::string problem = value_problem(*p, value);
    if (!problem.empty()) throw MethodSpecError(text + ": " + problem);
    spec.params[key] = value;
  }
  if (typed.back() == ':') throw MethodSpecError(text + ": expected key=value after ':'");
  if (info->check) {
    try {
      info->check(spec);
    } catch (const std::invalid_argument& e) {
      // The method's own messages start "method NAME: "; the spec says that already.
      std::string why = e.what();
      const std::string prefix = "method " + spec.name + ": ";
      if (why.compare(0, prefix.size(), prefix) == 0) why.erase(0, prefix.size());
      throw MethodSpecError(text + ": " + why);
    }
  }
  return spec;
}

std::vector<MethodSpec> parse_method_list(const std::string& csv) {
  std::vector<MethodSpec> out;
  std::stringstream in(csv);
  std::string item;
  while (std::getline(in, item, ','))
    if (!item.empty()) out.push_back(parse_method_spec(item));
  if (out.empty()) throw MethodSpecError("'" + csv + "': no methods given");
  return out;
}

std::unique_ptr<RayIntegrator> make_integrator(const MethodSpec& spec,
                                               const TransferFunctions& tf) {
  return method_schema(spec.name).make(spec, tf);
}

std::vector<std::string> method_names() {
  std::vector<std::string> out;
  for (const auto& e : registry()) out.push_back(e.name);
  return out;
}

std::vector<MethodSpec> default_methods() { return parse_method_list("exact,paper"); }

}  // namespace rayint
