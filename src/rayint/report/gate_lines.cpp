#include "rayint/report/gate_lines.hpp"

#include <cmath>
#include <cstdio>

#include "rayint/report/text_format.hpp"

namespace rayint {

// "PASS name: measured X (limit Y)"; a failure adds by how much.
std::string gate_lines(const GateReport& r) {
  std::string out;
  for (const GateCheck& c : r.checks) {
    out += std::string(c.pass ? "PASS " : "FAIL ") + c.name + ": measured " + g3(c.measured) +
           " (limit " + g3(c.limit) + ")";
    if (!c.pass && c.limit > 0 && std::isfinite(c.measured))
      out += ", " + g3(c.measured / c.limit) + " times the limit";
    if (!c.note.empty()) out += " -- " + c.note;
    out += "\n";
  }
  out += "gate: " + std::to_string(r.checks.size()) + " checks, " + std::to_string(r.failures()) +
         " failed: " + (r.pass() ? "PASS" : "FAIL") + "\n";
  return out;
}

std::string gate_progress_line(const GateProgress& p) {
  std::string line;
  appendf(line, "gate: %s %ld/%ld, %.0f s\n", p.phase.c_str(), p.done, p.total, p.seconds);
  return line;
}

}  // namespace rayint
