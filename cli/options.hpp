#pragma once
// Options several subcommands register the same way.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <string>

namespace rayint::cli {

// --threads N, checked >= 0 (0: all cores).
template <class Int>
CLI::Option* add_threads_option(CLI::App* cmd, Int& threads,
                                const std::string& help = "Worker threads (0: all cores)") {
  return cmd->add_option("--threads", threads, help)->check(CLI::NonNegativeNumber);
}

// -o,--output FILE: the command writes its report to FILE instead of stdout (emit, commands.hpp:
// atomically); `help` names the report where the default does not say enough.
inline CLI::Option* add_output_option(
    CLI::App* cmd, std::string& output,
    const std::string& help = "Write to this file instead of stdout") {
  return cmd->add_option("-o,--output", output, help);
}

// -q,--quiet: no progress on stderr.
inline CLI::Option* add_quiet_flag(CLI::App* cmd, bool& quiet) {
  return cmd->add_flag("-q,--quiet", quiet, "No progress on stderr");
}

// --strict-mesh: refuse inverted and degenerate tets (input/mesh_case_reader.hpp MeshReadOptions)
// instead of reorienting and dropping them.
inline CLI::Option* add_strict_mesh_flag(CLI::App* cmd, bool& strict) {
  return cmd->add_flag("--strict-mesh", strict,
                       "Mesh cases: refuse inverted, zero-volume and sliver tetrahedra (default: "
                       "reorient inverted ones, drop degenerate ones, and count both)");
}

// --cells own|split. A mesh file with hexahedra, wedges, pyramids or voxels is integrated in the
// cells' own interpolation by default ("own", mesh/cell_traversal.hpp: "mode": "own" in the JSON
// and on stderr); --cells split tetrahedralises it as VTK's vtkDataSetTriangleFilter does
// (mesh/cell_split.hpp) -- an approximation, said in the JSON ("mesh_repairs": {"cells":
// {"mode": "split", ...}}) and on stderr. Files of tetrahedra only take the tetrahedral path either way.
inline CLI::Option* add_cells_option(CLI::App* cmd, bool& split) {
  auto* o = cmd->add_option_function<std::string>(
      "--cells", [&split](const std::string& v) { split = v == "split"; },
      "Mesh files with hexahedra, wedges, pyramids, voxels: 'own' (default) integrates each cell in its "
      "own (isoparametric) interpolation; 'split' after VTK's tetrahedralisation "
      "(vtkDataSetTriangleFilter), an approximation of it");
  o->check(CLI::IsMember({"own", "split"}));
  return o;
}

// A tolerance (check and gradcheck --rel-tol, --abs-tol): a finite number >= 0 (CLI11's
// NonNegativeNumber lets "nan" through).
inline const CLI::Validator kTolerance(
    [](std::string& text) -> std::string {
      double x = 0.0;
      if (!CLI::detail::lexical_cast(text, x) || !std::isfinite(x) || x < 0.0)
        return "must be a finite number >= 0, got " + text;
      return {};
    },
    "TOL>=0");

// --rel-tol and --abs-tol of check and gradcheck: both tolerances (kTolerance) with their defaults
// shown; `rel_help` says what --rel-tol is relative to.
inline void add_tolerance_options(CLI::App* cmd, double& rel_tol, double& abs_tol, const std::string& rel_help) {
  cmd->add_option("--rel-tol", rel_tol, rel_help)->check(kTolerance)->capture_default_str();
  cmd->add_option("--abs-tol", abs_tol, "Absolute tolerance (see --rel-tol)")->check(kTolerance)->capture_default_str();
}

}  // namespace rayint::cli

namespace rayint::cli {

// Integer options accept the forms people type for large counts: `--photons 1e6`, `--count
// 2.5e5`, `--rays 1000.0` become 1000000, 250000, 1000. Only a number that is exactly an integer
// (and within +-2^63) is rewritten; `1.5` and `1e30` are left as they are for the option's own
// check to refuse. Applied to every INT/UINT option of every subcommand by
// accept_integer_float_forms.
inline std::string integer_from_float_form(std::string s) {
  if (s.find_first_of(".eE") == std::string::npos) return s;
  if (s.find_first_not_of("0123456789+-.eE") != std::string::npos) return s;
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(s, &used);
  } catch (const std::exception&) {
    return s;
  }
  if (used != s.size() || !(v == v) || v != static_cast<double>(static_cast<long long>(v)) ||
      std::abs(v) >= 9.2e18)
    return s;
  return std::to_string(static_cast<long long>(v));
}

// After that rewrite, an integer option's value must be a whole number (and >= 0 for an unsigned
// one): "must be a whole number >= 0, got -1" instead of CLI11's "Could not convert: --worst = -1",
// which does not say what would do. 20 digits and more are left to the conversion, which names the
// overflow.
inline std::string whole_number_error(const std::string& s, bool non_negative) {
  const std::size_t sign = !s.empty() && (s[0] == '+' || (s[0] == '-' && !non_negative)) ? 1 : 0;
  const bool digits = s.size() > sign && s.find_first_not_of("0123456789", sign) == std::string::npos;
  if (digits) return std::string();
  return std::string("must be a whole number") + (non_negative ? " >= 0" : "") + ", got " + s;
}

inline void accept_integer_float_forms(CLI::App& app) {
  for (CLI::Option* o : app.get_options()) {
    const std::string type = o->get_type_name();  // "INT", "UINT", then ":<validator>"...
    const bool non_negative = type.rfind("UINT", 0) == 0;
    if (type.rfind("INT", 0) == 0 || non_negative)
      o->transform(CLI::Validator(
          [non_negative](std::string& s) {
            s = integer_from_float_form(s);
            return whole_number_error(s, non_negative);
          },
          "", "integer float forms"));
  }
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) accept_integer_float_forms(*sub);
}

// Every FLOAT option of every subcommand refuses NaN and infinities ("--exposure nan", "--tau
// inf"): no rayint option has a meaning for them, and a NaN passes every `x > 0`-style check of
// a command's own (it compares false both ways). Applied by main next to accept_integer_float_forms;
// each option's own range (CLI::Range, a command's check) still applies.
inline std::string finite_number_error(const std::string& s) {
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);  // 1e400 overflows to inf (ERANGE): refused too
  if (end == s.c_str() || *end != '\0') return std::string();  // not a number: the conversion says so
  if (!std::isfinite(v)) return "must be a finite number, got " + s;
  return std::string();
}

// CLI11's PositiveNumber and NonNegativeNumber print their bounds with std::to_string: "Value -1
// not in range 0.000000 to 1797693134862315708145...(309 digits).000000". The same checks with
// a short message: "must be > 0, got -1" ("must be >= 0, got -1").
inline std::string sign_error(const std::string& s, bool zero_allowed) {
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (end == s.c_str() || *end != '\0') return std::string();  // not a number: the conversion says so
  if (zero_allowed ? v >= 0.0 : v > 0.0) return std::string();
  return std::string(zero_allowed ? "must be >= 0" : "must be > 0") + ", got " + s;
}

// Every option of every subcommand: FLOAT options refuse NaN and infinities; CLI11's
// PositiveNumber / NonNegativeNumber checks are replaced by the same checks with short messages.
inline void check_number_options(CLI::App& app) {
  for (CLI::Option* o : app.get_options()) {
    // CLI11's two validators have no name; their description is "POSITIVE" / "NONNEGATIVE".
    for (int i = 0;; ++i) {
      CLI::Validator* v = nullptr;
      try {
        v = o->get_validator(i);
      } catch (const CLI::OptionNotFound&) {
        break;
      }
      const std::string d = v->get_description();
      if (!v->get_active() || !v->get_name().empty() || (d != "POSITIVE" && d != "NONNEGATIVE")) continue;
      const bool zero_allowed = d == "NONNEGATIVE";
      v->active(false);
      o->check(CLI::Validator([zero_allowed](std::string& s) { return sign_error(s, zero_allowed); }, d,
                              zero_allowed ? "non-negative" : "positive"));  // named: not replaced again
    }
    if (o->get_type_name().rfind("FLOAT", 0) == 0) o->check(CLI::Validator(finite_number_error, "", "finite"));
  }
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) check_number_options(*sub);
}

}  // namespace rayint::cli
