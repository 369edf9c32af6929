#pragma once
// The common interface of every way to evaluate the ray integral (Williams & Max Eq. 4).
// A method is bound to one case's transfer functions (tables are built once there) and then
// integrates rays. Library code computes; it never prints.
#include <map>
#include <memory>
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
  virtual RayResult integrate(const Ray& ray, Diagnostics* diag) const = 0;
};

// A method that works on the pieces of a ray (its segments split at every transfer-function
// breakpoint, rho and kappa linear on each): holds the splitter bound to the case's functions.
class PieceIntegrator : public RayIntegrator {
 public:
  explicit PieceIntegrator(const TransferFunctions& tf) : splitter_(tf) {}

 protected:
  PieceSplitter splitter_;
};

// "name" or "name:key=value:key=value", e.g. "riemann:n=64", "ode:rtol=1e-8".
struct MethodSpec {
  std::string name;
  std::map<std::string, std::string> params;
  std::string label() const;  // canonical text form, used as the key in reports
  double number(const std::string& key, double fallback) const;
  std::string text(const std::string& key, const std::string& fallback) const;
};

MethodSpec parse_method_spec(const std::string& text);           // throws std::invalid_argument
std::vector<MethodSpec> parse_method_list(const std::string& csv);  // "exact,riemann:n=64"

// Builds the integrator for `spec` on the given transfer functions; throws
// std::invalid_argument for an unknown method or parameter.
std::unique_ptr<RayIntegrator> make_integrator(const MethodSpec& spec,
                                               const TransferFunctions& tf);
std::vector<std::string> method_names();

// Adds a method to the table (optional libraries, e.g. the VTK peer methods in src/rayint/vtk/).
// `params` lists the accepted parameter names, space-separated; call before any use from
// several threads. Throws std::invalid_argument if `name` is already registered.
using MethodFactory = std::unique_ptr<RayIntegrator> (*)(const MethodSpec&, const TransferFunctions&);
void register_method(const char* name, const char* params, MethodFactory make);
std::vector<MethodSpec> default_methods();  // what `rayint eval` runs without --methods

}  // namespace rayint
