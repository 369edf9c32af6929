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
#include "fuzz_checks.hpp"

namespace {

using rayint::fuzz::require;

constexpr const char* kSource = "fuzz-input.vts";

void check_mesh(const rayint::CellMesh& m) {
  require(m.cell_count() > 0 && m.offsets.size() == m.cell_count() + 1);
  require(m.cell_scalars.empty() ? m.scalars.size() == m.points.size() : m.cell_scalars.size() == m.cell_count());
  for (const auto& p : m.points) require(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]));
  for (double s : m.scalars) require(std::isfinite(s));
  for (double s : m.cell_scalars) require(std::isfinite(s));
  for (std::size_t c = 0; c < m.cell_count(); ++c) {
    require(m.nodes_of(c) == static_cast<std::size_t>(rayint::mesh_cell_nodes(static_cast<int>(m.types[c]))));
    for (std::size_t k = 0; k < m.nodes_of(c); ++k)
      require(m.cell(c)[k] >= 0 && static_cast<std::size_t>(m.cell(c)[k]) < m.points.size());
  }
  require(m.structured.has_value());
  const auto& d = *m.structured;
  require(static_cast<std::size_t>(d[0]) * static_cast<std::size_t>(d[1]) * static_cast<std::size_t>(d[2]) == m.points.size());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  rayint::fuzz::refusals_are_one_line(kSource, [&] {
    check_mesh(rayint::parse_vts(bytes, kSource));
  });
  return rayint::fuzz::refusals_are_one_line(kSource, [&] {
    check_mesh(rayint::parse_vtr(bytes, kSource));
  });
}
