#pragma once
// A closed range check for a floating-point option with its message in short form: CLI11's
// CLI::Range prints its bounds with std::to_string ("Value 2 not in range 0.000000 to 0.500000"
// for --alpha, whose lower bound is 1e-12), so a bound below 1e-6 read as 0 (issue 30, "One line,
// once": numbers in short form). The description stays CLI11's ("FLOAT in [1e-12 - 0.5]").
#include <CLI/CLI.hpp>
#include <cstdlib>
#include <sstream>
#include <string>

namespace rayint::cli {

inline CLI::Validator float_range(double lo, double hi) {
  const auto text = [](double x) {
    std::ostringstream s;
    s << x;  // 6 significant digits: 1e-12, 0.5, 1
    return s.str();
  };
  const std::string lo_text = text(lo), hi_text = text(hi);
  return CLI::Validator(
      [lo, hi, lo_text, hi_text](std::string& value) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(value.c_str(), &end);
        if (end == value.c_str() || *end != '\0') return std::string();  // not a number: the conversion says so
        if (v >= lo && v <= hi) return std::string();
        return "must be in [" + lo_text + ", " + hi_text + "], got " + value;
      },
      "FLOAT in [" + lo_text + " - " + hi_text + "]");
}

}  // namespace rayint::cli
