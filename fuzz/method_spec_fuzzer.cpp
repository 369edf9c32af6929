// libFuzzer target for the method-spec validator (rayint::parse_method_spec,
// integrators/integrator.hpp) on arbitrary bytes. Run it with
// `RAYINT_FUZZ_TARGET=method_spec scripts/fuzz.sh`. A finding is:
//   - a crash, sanitizer report, hang or leak;
//   - an exception other than rayint::MethodSpecError escaping (reported as a deadly signal);
//   - a refusal whose message is not one line of printable characters, starting with the spec
//     and ": " when the spec is printable (else its control bytes are escaped);
//   - an accepted spec that a factory could not read: every parameter of its method, given or
//     defaulted, must read through the typed getters (integer, number, text) without the
//     std::logic_error they raise for a value the validator should have refused, and a given
//     value must lie in its range / among its choices.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "rayint/integrators/integrator.hpp"
#include "fuzz_checks.hpp"

namespace {

using rayint::fuzz::require;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  rayint::MethodSpec spec;
  try {
    spec = rayint::parse_method_spec(text);
  } catch (const rayint::MethodSpecError& e) {
    const std::string what = e.what();
    bool printable = true;
    for (const char ch : text) printable = printable && ch >= 0x20 && ch < 0x7f;
    if (printable) require(what.compare(0, text.size() + 2, text + ": ") == 0);
    for (const char ch : what) require(ch >= 0x20 && ch < 0x7f);
    return 0;
  }
  const rayint::MethodSchema& method = rayint::method_schema(spec.name);
  for (const rayint::MethodParam& p : method.params) {
    if (!spec.has(p.name) && p.fallback.empty()) continue;  // optional, no default
    switch (p.type) {
      case rayint::MethodParam::Type::integer: {
        const int v = spec.integer(p.name);
        require(v >= p.min && v <= p.max);
        break;
      }
      case rayint::MethodParam::Type::number: {
        const double v = spec.number(p.name);
        require(std::isfinite(v));
        require(p.min_exclusive ? v > p.min : v >= p.min);
        if (p.has_max) require(p.max_exclusive ? v < p.max : v <= p.max);
        break;
      }
      case rayint::MethodParam::Type::choice: {
        const std::string v = spec.text(p.name);
        bool listed = false;
        for (const auto& c : p.choices) listed = listed || c == v;
        require(listed);
        break;
      }
    }
  }
  return 0;
}
