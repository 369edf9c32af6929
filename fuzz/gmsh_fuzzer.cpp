// libFuzzer target for the gmsh reader (rayint::parse_gmsh and parse_gmsh_cells, the latter then
// split by --cells split's rule; input/gmsh_reader.hpp: MSH 2.2/4.1,
// ASCII and binary) on arbitrary bytes; an accepted mesh is repaired and traversed
// (mesh_fuzz_checks.hpp). Run it with `RAYINT_FUZZ_TARGET=gmsh scripts/fuzz.sh`. Findings as in
// vtk_legacy_fuzzer.cpp.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "mesh_fuzz_checks.hpp"
#include "rayint/input/gmsh_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const std::string source = "fuzz.msh";
  using rayint::fuzz::refusals_are_one_line;
  refusals_are_one_line(source, [&] { rayint::fuzz::check_mesh(rayint::parse_gmsh(bytes, source), source); });
  return refusals_are_one_line(source, [&] { rayint::fuzz::check_cells(rayint::parse_gmsh_cells(bytes, source), source); });
}
