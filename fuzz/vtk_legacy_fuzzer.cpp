// libFuzzer target for the VTK legacy reader (rayint::parse_vtk_legacy, input/vtk_legacy_reader.hpp)
// on arbitrary bytes; an accepted mesh is repaired and traversed (mesh_fuzz_checks.hpp). Run it
// with `RAYINT_FUZZ_TARGET=vtk_legacy scripts/fuzz.sh`. Findings: a crash, sanitizer report, hang
// or leak; an exception other than InputError; an InputError that is not one line starting
// "<source>: "; an accepted mesh that breaks the reader's guarantees.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "mesh_fuzz_checks.hpp"
#include "rayint/input/vtk_legacy_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const std::string source = "fuzz.vtk";
  try {
    rayint::fuzz::check_mesh(rayint::parse_vtk_legacy(bytes, source), source);
  } catch (const rayint::InputError& e) {
    rayint::fuzz::check_message(e.what(), source);
  }
  return 0;
}
