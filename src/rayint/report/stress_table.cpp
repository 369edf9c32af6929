#include "rayint/report/stress_table.hpp"

#include <algorithm>
#include <cstdio>

#include "rayint/report/text_format.hpp"

namespace rayint {
namespace {

std::string duration(double s) {
  char buf[32];
  if (s < 120)
    std::snprintf(buf, sizeof buf, "%.0f s", s);
  else if (s < 7200)
    std::snprintf(buf, sizeof buf, "%.1f min", s / 60);
  else
    std::snprintf(buf, sizeof buf, "%.1f h", s / 3600);
  return buf;
}

// "erfcx 52% dawson 48%": shares of the branch counts.
std::string branch_shares(const std::map<std::string, long>& branches) {
  long total = 0;
  for (const auto& [k, v] : branches) total += v;
  std::string out;
  for (const auto& [k, v] : branches) {
    char buf[96];
    const double pct = 100.0 * static_cast<double>(v) / static_cast<double>(total);
    std::snprintf(buf, sizeof buf, pct >= 1 || pct == 0 ? "%s %.0f%%" : "%s %.1g%%", k.c_str(), pct);
    out += (out.empty() ? "" : " ") + std::string(buf);
  }
  return out;
}

std::string method_row(const std::string& regime, const std::string& samples, const std::string& pieces,
                       const MethodStress& m) {
  std::string line;
  appendf(line, "%-20s %-14s %8s %9s %9s %9s %9s %9s %9s %9s %7ld %6ld %6ld  %s\n", regime.c_str(),
          m.method.c_str(), samples.c_str(), pieces.c_str(), g3(m.rel.max).c_str(),
          g3(m.rel.p99).c_str(), g3(m.rel.median).c_str(), g3(m.ulp.max).c_str(),
          g3(m.ulp.p99).c_str(), g3(m.ulp.median).c_str(), m.non_finite, m.failures, m.underflow,
          branch_shares(m.branches).c_str());
  return line;
}

}  // namespace

std::string stress_table(const StressReport& r) {
  std::string methods;
  for (const auto& m : r.methods) methods += (methods.empty() ? "" : ",") + m;
  std::string out = "rayint stress: seed " + std::to_string(r.seed) + ", " +
                    std::to_string(r.count) + " pieces requested, methods " + methods + "\n";
  appendf(out, "%-20s %-14s %8s %9s %9s %9s %9s %9s %9s %9s %7s %6s %6s  %s\n", "regime", "method",
          "samples", "pieces", "max rel", "p99 rel", "med rel", "max ulp", "p99 ulp", "med ulp",
          "nonfin", "failed", "uflow", "branches");
  out += std::string(157, '-') + "\n";
  long samples = 0, pieces = 0;
  for (const auto& reg : r.regimes) {
    samples += reg.samples;
    pieces += reg.pieces;
    for (const auto& m : reg.methods)
      out += method_row(reg.regime, std::to_string(reg.samples), std::to_string(reg.pieces), m);
  }
  out += std::string(157, '-') + "\n";
  for (const auto& m : r.overall)
    out += method_row("all", std::to_string(samples), std::to_string(pieces), m);
  out += "\nrel: relative error of the intensity (largest over a sample's channels); ulp: the same\n"
         "in units in the last place (both over the samples that did not fail); nonfin: non-finite\n"
         "results or failures; failed: of those, samples where the method threw; uflow: samples with\n"
         "a reference below 1e-290 in magnitude, scored by absolute error instead (largest:";
  double max_uf = 0;
  for (const auto& m : r.overall) max_uf = std::max(max_uf, m.max_abs_error_underflow);
  out += " " + g3(max_uf) + ").\n";
  double max_bound = 0;
  long ref_failures = 0;
  for (const auto& reg : r.regimes) {
    max_bound = std::max(max_bound, reg.max_reference_rel_bound);
    ref_failures += reg.reference_failures;
  }
  out += "Reference: largest claimed relative error bound " + g3(max_bound) + ", " +
         std::to_string(ref_failures) + " failures.\n";
  bool any_file = false;
  for (const auto& reg : r.regimes)
    for (const auto& m : reg.methods)
      for (const WorstSample* w : {&m.worst, &m.worst_finite})
        if (!w->file.empty()) {
          if (!any_file) out += "Worst samples (replay with `rayint eval FILE --methods METHOD`):\n";
          any_file = true;
          out += "  " + w->file + "  (" +
                 (w->non_finite ? (w->failure.empty() ? std::string("non-finite") : "failed: " + w->failure)
                                : "rel " + g3(w->rel_error)) +
                 ")\n";
        }
  return out;
}


std::string stress_progress_line(const StressProgress& p) {
  const double rate = p.seconds > 0 ? static_cast<double>(p.pieces_done) / p.seconds : 0.0;
  const double left = rate > 0 ? static_cast<double>(p.pieces_total - p.pieces_done) / rate : 0.0;
  std::string line;
  appendf(line, "stress: %ld/%ld pieces (%.0f%%), %ld/%ld samples, %.0f pieces/s, %s elapsed%s\n",
          p.pieces_done, p.pieces_total,
          100.0 * static_cast<double>(p.pieces_done) / static_cast<double>(p.pieces_total),
          p.samples_done, p.samples_total, rate, duration(p.seconds).c_str(),
          p.pieces_done < p.pieces_total ? (", about " + duration(left) + " left").c_str() : "");
  return line;
}

}  // namespace rayint
