#include "rayint/report/junit.hpp"

#include <cmath>
#include <string>

#include "rayint/report/text_format.hpp"

namespace rayint {
namespace {

std::string escape(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (char ch : s) {
    const unsigned char c = static_cast<unsigned char>(ch);
    switch (ch) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += (c < 0x20 && ch != '\t' && ch != '\n') ? ' ' : ch;
    }
  }
  return out;
}

const char* kChannelNames[3] = {"r", "g", "b"};

}  // namespace

std::string junit_measure(double measured, double limit) {
  std::string factor;
  if (limit > 0.0 && std::isfinite(measured)) factor = g3(measured / limit);
  else if (measured == 0.0) factor = "0";
  else factor = "inf";
  return "measured " + g3(measured) + ", limit " + g3(limit) + ", factor " + factor;
}

std::string junit_xml(const std::vector<JUnitSuite>& suites) {
  long tests = 0, failures = 0;
  for (const auto& s : suites)
    for (const auto& c : s.cases) {
      ++tests;
      failures += c.pass ? 0 : 1;
    }
  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += "<testsuites name=\"rayint\" tests=\"" + std::to_string(tests) + "\" failures=\"" +
         std::to_string(failures) + "\" errors=\"0\">\n";
  for (const auto& s : suites) {
    long f = 0;
    for (const auto& c : s.cases) f += c.pass ? 0 : 1;
    out += "  <testsuite name=\"" + escape(s.name) + "\" tests=\"" + std::to_string(s.cases.size()) +
           "\" failures=\"" + std::to_string(f) + "\" errors=\"0\" skipped=\"0\">\n";
    for (const auto& c : s.cases) {
      out += "    <testcase classname=\"" + escape(c.classname) + "\" name=\"" + escape(c.name) + "\"";
      if (c.pass) {
        out += "/>\n";
        continue;
      }
      out += ">\n      <failure message=\"" + escape(c.message) + "\" type=\"tolerance\">" +
             escape(c.detail.empty() ? c.message : c.detail) + "</failure>\n    </testcase>\n";
    }
    out += "  </testsuite>\n";
  }
  out += "</testsuites>\n";
  return out;
}

JUnitSuite gate_junit(const GateReport& report) {
  JUnitSuite s{"rayint gate", {}};
  for (const GateCheck& c : report.checks) {
    JUnitCase t{"rayint.gate", c.name, c.pass, {}, {}};
    if (!c.pass) {
      t.message = c.name + ": " + junit_measure(c.measured, c.limit);
      if (!c.note.empty()) t.message += " -- " + c.note;
    }
    s.cases.push_back(t);
  }
  return s;
}

JUnitSuite check_junit(const CheckResult& r) {
  JUnitSuite s{"rayint check " + r.case_name, {}};
  for (std::size_t i = 0; i < r.rays.size(); ++i) {
    const RayCheck& ray = r.rays[i];
    JUnitCase t{"rayint.check." + r.case_name, "ray[" + std::to_string(i) + "]", ray.pass, {}, {}};
    if (!ray.pass) {
      int worst = 0;
      double worst_ratio = -1.0;
      for (int c = 0; c < kChannels; ++c) {
        const ChannelCheck& ch = ray.channel[c];
        const double ratio = ch.allowed > 0 ? ch.abs_error / ch.allowed : INFINITY;
        if (!ch.pass && (ratio > worst_ratio || std::isnan(ratio))) {
          worst = c;
          worst_ratio = ratio;
        }
      }
      const ChannelCheck& ch = ray.channel[worst];
      t.message = "ray[" + std::to_string(i) + "] channel " + kChannelNames[worst] +
                  ": |got - expected| " + junit_measure(ch.abs_error, ch.allowed) + " (expected " +
                  g3(ch.expected) + ", got " + g3(ch.got) + ")";
      if (!ray.expected_failure.empty()) t.message += "; no expected value: " + ray.expected_failure;
    }
    s.cases.push_back(t);
  }
  return s;
}

JUnitSuite image_check_junit(const std::string& case_name, const ImageComparison& c) {
  JUnitSuite s{"rayint check " + case_name + " (image)", {}};
  const std::string cls = "rayint.check." + case_name;
  JUnitCase all{cls, "pixels_within_tolerance", c.pass, {}, {}};
  if (!c.pass) {
    all.message = std::to_string(c.failed_pixels) + " of " + std::to_string(c.pixels) +
                  " pixels outside tolerance: failing pixels " +
                  junit_measure(static_cast<double>(c.failed_pixels), 0.0);
    if (!c.worst.empty()) {
      const PixelDiff& w = c.worst.front();
      all.message += "; worst pixel(" + std::to_string(w.x) + "," + std::to_string(w.y) + ") channel " +
                     kChannelNames[w.channel] + ": |got - expected| " + junit_measure(w.abs_error, w.allowed);
    }
  }
  s.cases.push_back(all);
  for (const PixelDiff& w : c.worst) {
    JUnitCase t{cls, "pixel(" + std::to_string(w.x) + "," + std::to_string(w.y) + ")", w.pass, {}, {}};
    if (!w.pass)
      t.message = "pixel(" + std::to_string(w.x) + "," + std::to_string(w.y) + ") channel " +
                  kChannelNames[w.channel] + ": |got - expected| " + junit_measure(w.abs_error, w.allowed) +
                  " (expected " + g3(w.expected) + ", got " + g3(w.got) + ")";
    s.cases.push_back(t);
  }
  return s;
}

JUnitSuite z_test_junit(const std::string& case_name, const ZTestResult& z, double min_fraction) {
  JUnitSuite s{"rayint check " + case_name + " (Monte Carlo image)", {}};
  JUnitCase t{"rayint.check." + case_name, "z_test_fraction_passing", z.pass, {}, {}};
  if (!z.pass)
    t.message = "fraction of pixel channels passing the z-test " + junit_measure(z.fraction_passing, min_fraction) +
                " (lower limit; " + std::to_string(z.rejected) + " of " + std::to_string(z.tests) +
                " rejected, worst pixel(" + std::to_string(z.worst_x) + "," + std::to_string(z.worst_y) +
                ") channel " + kChannelNames[z.worst_channel] + ", |z| " + g3(z.worst_z) + ")";
  s.cases.push_back(t);
  return s;
}

}  // namespace rayint
