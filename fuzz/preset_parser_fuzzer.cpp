// libFuzzer target for the ParaView preset reader and importer of `rayint tf import`
// (rayint::import_paraview_preset_text, input/paraview_preset.hpp) on arbitrary bytes, under each
// opacity convention. Run it with `RAYINT_FUZZ_TARGET=preset_parser scripts/fuzz.sh`. A finding is:
//   - a crash, sanitizer report, hang or leak;
//   - an exception other than rayint::InputError escaping (reported as a deadly signal);
//   - an InputError whose message is not one line starting with "<source>: ";
//   - an accepted import that breaks the guarantees of model/tf_import.hpp: every function has a
//     point, scalars non-decreasing and at most twice in a row (a jump), values finite and >= 0,
//     max deviation finite.
// Paths of issue 27 reached through the bytes: UseLogScale, Step and "CIELAB" colour spaces,
// repeated RGBPoints scalars, IndexedColors refusal, the default opacity ramp, --index selection.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "rayint/input/paraview_preset.hpp"
#include "fuzz_checks.hpp"

namespace {

using rayint::fuzz::require;

constexpr const char* kSource = "fuzz-preset.json";

void check_message(const std::string& what) {
  require(what.compare(0, 18, "fuzz-preset.json: ") == 0 || what.compare(0, 6, "fuzz: ") == 0);
  require(what.find('\n') == std::string::npos && what.find('\r') == std::string::npos);
}

void check_function(const rayint::PiecewiseLinear& f) {
  require(!f.scalar.empty() && f.scalar.size() == f.value.size());
  for (std::size_t k = 0; k < f.scalar.size(); ++k) {
    require(std::isfinite(f.scalar[k]) && std::isfinite(f.value[k]) && f.value[k] >= 0.0);
    if (k > 0) require(f.scalar[k] >= f.scalar[k - 1]);
    if (k > 1) require(f.scalar[k] > f.scalar[k - 2]);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  // The first byte picks the convention; a loose tolerance keeps the adaptive work bounded.
  const rayint::OpacityConvention conventions[] = {
      rayint::OpacityConvention::density, rayint::OpacityConvention::unit_distance,
      rayint::OpacityConvention::sample_distance, rayint::OpacityConvention::nerf_sigma};
  rayint::PresetImportRequest r;
  r.file = kSource;
  r.request_source = "fuzz";
  r.options.convention = conventions[size > 0 ? data[0] % 4 : 0];
  r.options.distance = 0.5;
  r.options.tolerance = 1e-3;
  // The second byte: a constant opacity or the preset's Points / ParaView's default ramp, and a
  // selection by index (the name path is taken when the file holds one preset).
  const std::uint8_t second = size > 1 ? data[1] : 0;
  if (second & 1) r.constant_opacity = 0.25;
  if (second & 2) r.index = static_cast<std::size_t>(second >> 2);
  try {
    const rayint::PresetImport imp = rayint::import_paraview_preset_text(text, r);
    for (int c = 0; c < 3; ++c) {
      check_function(imp.result.transfer.density[c]);
      check_function(imp.result.transfer.color[c]);
    }
    require(std::isfinite(imp.result.density.max_deviation) && std::isfinite(imp.result.color.max_deviation));
  } catch (const rayint::InputError& e) {
    check_message(e.what());
  }
  return 0;
}
