// libFuzzer target for the slab-scene reader (rayint::parse_slab_scene, input/slab_scene_reader.hpp)
// on arbitrary bytes: the medium, phase function (including "legendre" coefficients and
// "tabulated" points, turned into Legendre coefficients by scattering/pn.cpp), light, detectors
// and Lambertian ground. Run it with `RAYINT_FUZZ_TARGET=slab_scene_parser scripts/fuzz.sh`.
// Findings: a crash, sanitizer report, hang, leak or out-of-memory; an exception other than
// InputError; an InputError that is not one line starting "<source>: "; a scene accepted that
// breaks the format (numbers out of range, coefficients not starting at 1 or not in (-1, 1)).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "rayint/core/error.hpp"
#include "rayint/input/slab_scene_reader.hpp"
#include "fuzz_checks.hpp"

namespace {

using rayint::fuzz::require;

constexpr const char* kSource = "fuzz-slab-scene.json";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  return rayint::fuzz::refusals_are_one_line(kSource, [&] {
    const rayint::SlabScene s = rayint::parse_slab_scene(text, kSource);
    const rayint::SlabProblem& p = s.problem;
    require(std::isfinite(p.tau) && p.tau > 0);
    require(p.albedo >= 0 && p.albedo <= 1 && p.ground_albedo >= 0 && p.ground_albedo <= 1);
    if (!s.legendre.empty()) {
      require(s.legendre[0] == 1);
      for (std::size_t l = 1; l < s.legendre.size(); ++l) require(std::fabs(s.legendre[l]) < 1 || s.phase_name == "tabulated");
      for (double c : s.legendre) require(std::isfinite(c));
    }
  });
}
