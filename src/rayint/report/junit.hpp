#pragma once
// JUnit XML, the report CI systems (GitLab, Jenkins, GitHub test reporters) read: one
// <testsuites> holding one <testsuite> per rayint command run, one <testcase> per check, and for
// a failed check a <failure message="..."> naming the measured value, the limit and the factor
// measured / limit. Written for `rayint check --junit FILE` and `rayint gate --junit FILE`.
#include <string>
#include <vector>

#include "rayint/render/image_compare.hpp"
#include "rayint/studies/check.hpp"
#include "rayint/studies/gate.hpp"

namespace rayint {

struct JUnitCase {
  std::string classname;  // e.g. "rayint.gate", "rayint.check.paper-figure-2"
  std::string name;       // the check's name
  bool pass = true;
  std::string message;    // the failure's one-line message (empty when passing)
  std::string detail;     // longer text inside <failure> (optional)
};

struct JUnitSuite {
  std::string name;
  std::vector<JUnitCase> cases;
};

// Well-formed XML 1.0: attribute and text values escaped (&, <, >, ", ') and control characters
// other than tab / newline replaced by spaces.
std::string junit_xml(const std::vector<JUnitSuite>& suites);

// "measured X, limit Y, factor Z" (factor = measured / limit; "inf" when the limit is 0).
std::string junit_measure(double measured, double limit);

// One testcase per gate check (name = the check's name).
JUnitSuite gate_junit(const GateReport& report);
// One testcase per ray (the worst channel in the message).
JUnitSuite check_junit(const CheckResult& result);
// Image check: "pixels_within_tolerance" (measured: failing pixels, limit 0) and one testcase per
// listed worst pixel, "pixel(x,y)", which fails when that pixel does.
JUnitSuite image_check_junit(const std::string& case_name, const ImageComparison& comparison);
// Monte Carlo mode: one testcase "z_test_fraction_passing" (measured: the fraction, limit:
// min_fraction; the failure names the worst pixel).
JUnitSuite z_test_junit(const std::string& case_name, const ZTestResult& z, double min_fraction);

}  // namespace rayint
