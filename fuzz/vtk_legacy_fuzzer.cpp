// libFuzzer target for the VTK legacy reader (rayint::parse_vtk_legacy, parse_vtk_legacy_cells and
// parse_vtk_legacy_image,
// input/vtk_legacy_reader.hpp: unstructured grids and STRUCTURED_POINTS images) on arbitrary
// bytes; an accepted mesh is repaired and traversed (mesh_fuzz_checks.hpp), an accepted image
// must hold one finite value per point. Run it
// with `RAYINT_FUZZ_TARGET=vtk_legacy scripts/fuzz.sh`. Findings: a crash, sanitizer report, hang
// or leak; an exception other than InputError; an InputError that is not one line starting
// "<source>: "; an accepted mesh that breaks the reader's guarantees.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "mesh_fuzz_checks.hpp"
#include "rayint/input/vtk_legacy_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const std::string source = "fuzz.vtk";
  using rayint::fuzz::refusals_are_one_line;
  using rayint::fuzz::require;
  refusals_are_one_line(source, [&] { rayint::fuzz::check_mesh(rayint::parse_vtk_legacy(bytes, source), source); });
  // every linear cell kept (parse_vtk_legacy_cells), then split
  refusals_are_one_line(source, [&] { rayint::fuzz::check_cells(rayint::parse_vtk_legacy_cells(bytes, source), source); });
  return refusals_are_one_line(source, [&] {
    const rayint::VoxelGrid g = rayint::parse_vtk_legacy_image(bytes, source);
    const auto& d = g.dims();
    require(g.values().size() == static_cast<std::size_t>(d[0]) * static_cast<std::size_t>(d[1]) * static_cast<std::size_t>(d[2]));
    for (const double v : g.values()) require(std::isfinite(v));
  });
}
