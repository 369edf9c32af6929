#pragma once
// The common interface of every way to evaluate the ray integral (Williams & Max Eq. 4).
// A method is bound to one case's transfer functions (tables are built once there) and then
// integrates rays. Library code computes; it never prints.
#include <cstddef>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "rayint/model/pieces.hpp"
#include "rayint/model/ray.hpp"

namespace rayint {

// Which branches/series a method took and other counters (steps, terms), for introspection.
struct Diagnostics {
  std::map<std::string, long> branches;
  std::map<std::string, double> stats;  // e.g. "steps", "max_terms"
  void count(const std::string& branch, long n = 1) { branches[branch] += n; }
  void max_stat(const std::string& key, double v) {
    auto it = stats.find(key);
    if (it == stats.end() || v > it->second) stats[key] = v;
  }
  void add_stat(const std::string& key, double v) { stats[key] += v; }
};

struct RayResult {
  Rgb intensity{};      // light reaching the eye
  Rgb transmittance{};  // fraction of the background reaching the eye
  // Before anything is composited: the background, transmitted whole.
  static RayResult of_background(const Rgb& background) { return {background, {1.0, 1.0, 1.0}}; }
};

class RayIntegrator {
 public:
  virtual ~RayIntegrator() = default;
  // `diag` may be null (timing loops pass null so bookkeeping costs nothing).
  // A ray with quadratic segments (Ray::quadratic: chords of quadratic tetrahedra) goes to a
  // method that takes them (takes_quadratic_segments); any other method throws
  // std::invalid_argument (kLinearSegmentsOnly) rather than integrate a scalar it cannot see.
  RayResult integrate(const Ray& ray, Diagnostics* diag) const {
    if (!ray.quadratic.empty() && !takes_quadratic_segments() && has_quadratic_segments(ray))
      throw std::invalid_argument(kLinearSegmentsOnly);
    return integrate_segments(ray, diag);
  }
  // out[i] = integrate(rays[i], nullptr) for i < n, bit for bit; a method may compute the rays
  // together (ExactIntegrator: one kernel batch over the pieces of all n rays, issue 33).
  // `pieces`, when not null: a method that splits the rays at the transfer functions'
  // breakpoints on the way adds their piece count (PieceSplitter::append's, the render's
  // statistic) to *pieces and returns true; any other leaves it and returns false (the caller
  // counts them itself).
  bool integrate_many(const Ray* rays, std::size_t n, RayResult* out, long* pieces = nullptr) const {
    for (std::size_t i = 0; i < n; ++i)
      if (!rays[i].quadratic.empty() && !takes_quadratic_segments() && has_quadratic_segments(rays[i]))
        throw std::invalid_argument(kLinearSegmentsOnly);
    return integrate_many_segments(rays, n, out, pieces);
  }
  // True for the methods that evaluate the scalar along a segment where they need it (sampling
  // methods: riemann, nerf, rk4; SamplingIntegrator below) and so take quadratic segments as they are.
  virtual bool takes_quadratic_segments() const { return false; }

  static constexpr const char* kLinearSegmentsOnly =
      "the scalar is quadratic along this ray's chords (quadratic tetrahedra) and this method takes "
      "linear segments only (its closed form, table or pieces assume a scalar linear along each segment)";

 protected:
  virtual RayResult integrate_segments(const Ray& ray, Diagnostics* diag) const = 0;
  // integrate_many's rays, checked; one at a time unless a method does better. Returns whether
  // it counted the pieces (see integrate_many; `pieces` may be null).
  virtual bool integrate_many_segments(const Ray* rays, std::size_t n, RayResult* out, long* /*pieces*/) const {
    for (std::size_t i = 0; i < n; ++i) out[i] = integrate_segments(rays[i], nullptr);
    return false;
  }
};

// A method that works on the pieces of a ray (its segments split at every transfer-function
// breakpoint, rho and kappa linear on each): holds the splitter bound to the case's functions.
class PieceIntegrator : public RayIntegrator {
 public:
  explicit PieceIntegrator(const TransferFunctions& tf) : splitter_(tf) {}

 protected:
  PieceSplitter splitter_;
};

// A sampling method (riemann, rk4, nerf): evaluates the transfer functions at the scalar of the
// points where it samples a segment, so it takes quadratic chords (model/ray.hpp) as they are.
class SamplingIntegrator : public RayIntegrator {
 public:
  bool takes_quadratic_segments() const final { return true; }

 protected:
  explicit SamplingIntegrator(const TransferFunctions& tf) : tf_(tf) {}
  const TransferFunctions& tf_;
};

// "name" or "name:key=value:key=value", e.g. "riemann:n=64", "ode:rtol=1e-8".
// A spec from parse_method_spec has been checked against its method's parameter table
// (MethodParam below): every value has its type and lies in its range, so a factory reads it
// without checking again.
struct MethodSpec {
  std::string name;
  std::map<std::string, std::string> params;  // as given
  std::string spelling;  // the text as typed ("" when built in code); the key in reports
  // The key in reports and JSON: the spec as the user typed it (e.g. "nerf:n=64:at=near").
  std::string label() const;
  // name, then the parameters sorted by key: one text per setting whatever the order typed;
  // used to match a method across runs (drift baselines, a method named twice in a gate).
  std::string canonical() const;
  bool has(const std::string& key) const { return params.count(key) > 0; }
  // The value given, else the default in the method's parameter table. For a spec of a
  // registered method (make_integrator's factories); throws std::logic_error for a key the
  // table does not list or that has no default.
  double number(const std::string& key) const;
  int integer(const std::string& key) const;
  std::string text(const std::string& key) const;
  // With the fallback in the call: for specs outside the method table (scene effects).
  double number(const std::string& key, double fallback) const;
  std::string text(const std::string& key, const std::string& fallback) const;
};

// One parameter of a method. This table is the one source of what a method accepts: the
// validator (parse_method_spec), the factories (MethodSpec::number/integer/text read its
// defaults) and `rayint methods` all read it.
struct MethodParam {
  enum class Type { integer, number, choice };
  std::string name;
  Type type = Type::number;
  std::string fallback;  // the default as text; "" = no default (what absence means is in `about`)
  double min = 0.0, max = 0.0;  // integer, number: the allowed range (see the flags below)
  bool has_min = false, has_max = false;
  bool min_exclusive = false;        // the value must be > min (not >=)
  bool max_exclusive = false;        // the value must be < max (not <=)
  std::vector<std::string> choices;  // choice: the allowed values
  std::string about;                 // one line for `rayint methods`
  std::string limit;                 // where `max` comes from (e.g. the memory it takes); may be ""
};
const char* type_name(MethodParam::Type t);  // "integer", "number", "choice"
// The allowed values in words, e.g. "an integer in [1, 1e9]", "a number > 0", "btf or ftb".
std::string allowed_values(const MethodParam& p);

// Table rows, e.g. integer_param("n", "64", 1, 1e9, "samples per segment").
MethodParam integer_param(const std::string& name, const std::string& fallback, double min,
                          double max, const std::string& about, const std::string& limit = "");
// A number > min (min_exclusive) or >= min, and < max or <= max (max = inf: no upper bound).
MethodParam number_param(const std::string& name, const std::string& fallback, double min,
                         bool min_exclusive, double max, bool max_exclusive,
                         const std::string& about, const std::string& limit = "");
MethodParam choice_param(const std::string& name, const std::string& fallback,
                         std::vector<std::string> choices, const std::string& about);

using MethodFactory = std::unique_ptr<RayIntegrator> (*)(const MethodSpec&, const TransferFunctions&);

// A method: its name, one line on what it is, its parameters, its factory, and (optional) a
// check of combinations one parameter's range cannot state (riemann: n or dt, not both); the
// check throws std::invalid_argument with a message that does not repeat the spec.
struct MethodSchema {
  std::string name;
  std::string about;
  std::vector<MethodParam> params;
  MethodFactory make = nullptr;
  void (*check)(const MethodSpec&) = nullptr;
};

// A method spec that is not valid: unknown method or parameter, a value of the wrong type or out
// of range. what() is one line starting with the spec, e.g.
// "riemann:n=0: n must be an integer >= 1".
struct MethodSpecError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

MethodSpec parse_method_spec(const std::string& text);             // throws MethodSpecError
std::vector<MethodSpec> parse_method_list(const std::string& csv);  // "exact,riemann:n=64"

// Builds the integrator for `spec` on the given transfer functions. A spec from
// parse_method_spec is valid; what can still fail is the method on this case (e.g. particle on
// several transfer functions), as std::invalid_argument.
std::unique_ptr<RayIntegrator> make_integrator(const MethodSpec& spec,
                                               const TransferFunctions& tf);
std::vector<std::string> method_names();
const std::vector<MethodSchema>& method_table();  // every registered method, in order
const MethodSchema& method_schema(const std::string& name);  // throws MethodSpecError if unknown

// Adds a method to the table (optional libraries, e.g. the VTK peer methods in src/rayint/vtk/).
// Call before any use from several threads. Throws std::invalid_argument if `info.name` is
// already registered.
void register_method(MethodSchema info);
std::vector<MethodSpec> default_methods();  // what `rayint eval` runs without --methods

}  // namespace rayint
