// libFuzzer target for rayint's structured-grid readers (rayint::parse_vts and rayint::parse_vtr,
// input/vtk_xml_reader.hpp) on arbitrary bytes: each input is given to both. Built by
// fuzz/CMakeLists.txt with -fsanitize=fuzzer,address,undefined; run it with
// RAYINT_FUZZ_TARGET=structured_grid scripts/fuzz.sh (seeds: tests/fixtures/readers/cells-*.vts,
// cells-*.vtr). A finding is any of:
//   - a crash, sanitizer report, hang, leak or out-of-memory;
//   - an exception other than rayint::InputError escaping the reader;
//   - an InputError whose message is not one line starting with "<source>: ";
//   - a mesh accepted although it breaks the reader's guarantees: at least one cell, node counts
//     per cell type, indices in range, finite points and scalars, one scalar per point or cell,
//     structured dimensions that match the cells.
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

constexpr const char* kSource = "fuzz-input.vts";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  rayint::fuzz::refusals_are_one_line(kSource, [&] {
    rayint::fuzz::check_structured_cells(rayint::parse_vts(bytes, kSource));
  });
  return rayint::fuzz::refusals_are_one_line(kSource, [&] {
    rayint::fuzz::check_structured_cells(rayint::parse_vtr(bytes, kSource));
  });
}
