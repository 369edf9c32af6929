// libFuzzer target for rayint's .vti readers (rayint::parse_vti, and parse_vti_cells: the image
// as a mesh of its voxels; input/vtk_xml_reader.hpp) on arbitrary bytes. Built by fuzz/CMakeLists.txt with -fsanitize=fuzzer,address,undefined; run it
// with RAYINT_FUZZ_TARGET=vti_reader scripts/fuzz.sh (seeds: tests/fixtures/vtkxml/*.vti). A
// finding is any of:
//   - a crash, sanitizer report, hang, leak or out-of-memory;
//   - an exception other than rayint::InputError escaping the reader (the VoxelGrid constructor's
//     std::invalid_argument included: the reader must refuse what the grid would refuse);
//   - an InputError whose message is not one line starting with "<source>: ";
//   - a grid accepted although it breaks the reader's guarantees: >= 2 points per axis, one finite
//     value per point, spacing > 0, finite bounds, a finite orthonormal Direction;
//   - a voxel mesh accepted with a non-finite point or scalar, a cell index out of range, or
//     point dimensions that do not match its points.
// Each check traps, so the input is saved as a crash artifact.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "rayint/core/error.hpp"
#include "rayint/input/vtk_xml_reader.hpp"
#include "mesh_fuzz_checks.hpp"

namespace {

using rayint::fuzz::require;

constexpr const char* kSource = "fuzz-input.vti";

void check_grid(const rayint::VoxelGrid& g) {
  std::size_t n = 1;
  for (int a = 0; a < 3; ++a) {
    require(g.dims()[static_cast<std::size_t>(a)] >= 2 && g.spacing()[a] > 0);
    require(std::isfinite(g.lower()[a]) && std::isfinite(g.upper()[a]));
    n *= static_cast<std::size_t>(g.dims()[static_cast<std::size_t>(a)]);
  }
  require(g.values().size() == n);
  for (double v : g.values()) require(std::isfinite(v));
  require(rayint::check_direction(g.placement().direction).empty() && g.placement().pivot.allFinite());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  rayint::fuzz::refusals_are_one_line(kSource, [&] { check_grid(rayint::parse_vti(bytes, kSource)); });
  return rayint::fuzz::refusals_are_one_line(kSource, [&] { rayint::fuzz::check_structured_cells(rayint::parse_vti_cells(bytes, kSource)); });
}
