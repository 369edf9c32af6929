// libFuzzer target for rayint's parallel structured-grid readers (rayint::parse_pvts and
// rayint::parse_pvtr, input/vtk_xml_reader.hpp) on arbitrary bytes. A parallel file names other
// files, so an input is the parallel file followed by its pieces, the parts separated by the line
// "--piece--": the k-th piece file the reader asks for (whatever its name) gets part k + 1, and a
// request beyond the last part is a missing file (an InputError, as from the real loader). Each
// input is given to both readers. Built by fuzz/CMakeLists.txt with
// -fsanitize=fuzzer,address,undefined; run it with RAYINT_FUZZ_TARGET=parallel_grid scripts/fuzz.sh
// (seeds: fuzz/seeds/parallel_grid/, the VTK-written fixtures of
// tests/fixtures/readers/parallel/ joined this way). A finding is any of:
//   - a crash, sanitizer report, hang, leak or out-of-memory;
//   - an exception other than rayint::InputError escaping the reader;
//   - an InputError whose message is not one line starting with "<source>: ", "<source> (N
//     pieces): " (the joined grid's assembly) or, for a piece's own refusals, "<the piece path
//     the reader resolved>: ";
//   - a mesh accepted although it breaks the reader's guarantees: at least one cell, node counts
//     per cell type, indices in range, finite points and scalars, one scalar per point or cell,
//     structured dimensions that match the points and the cells.
// Each check traps, so the input is saved as a crash artifact.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "rayint/core/error.hpp"
#include "rayint/input/vtk_xml_reader.hpp"
#include "mesh_fuzz_checks.hpp"

namespace {

using rayint::fuzz::require;

constexpr const char* kSource = "fuzz-input.pvts";
constexpr std::string_view kSeparator = "\n--piece--\n";

// What every structured grid keeps (mesh_fuzz_checks.hpp), and the joined grid's cells: the
// structured dimensions' cells less the ghost cells dropped.
void check_mesh(const rayint::CellMesh& m) {
  rayint::fuzz::check_structured_cells(m);
  const auto& d = *m.structured;
  require(static_cast<std::size_t>(d[0] - 1) * static_cast<std::size_t>(d[1] - 1) * static_cast<std::size_t>(d[2] - 1) ==
          m.cell_count() + m.info.ghost_cells);
}

std::vector<std::string_view> split(std::string_view bytes) {
  std::vector<std::string_view> parts;
  for (;;) {
    const std::size_t at = bytes.find(kSeparator);
    parts.push_back(bytes.substr(0, at));
    if (at == std::string_view::npos) return parts;
    bytes.remove_prefix(at + kSeparator.size());
  }
}

template <class Parse>
void run(const std::vector<std::string_view>& parts, Parse parse) {
  std::size_t next = 1;
  std::vector<std::string> asked;  // the piece paths the reader resolved, in order
  const rayint::PieceFileLoader load = [&](const std::string& path) -> std::string {
    asked.push_back(path);
    if (next >= parts.size()) throw rayint::InputError(std::string(kSource) + ": P: the piece " + path + " does not exist");
    return std::string(parts[next++]);
  };
  try {
    check_mesh(parse(std::string_view(parts[0]), load));
  } catch (const rayint::InputError& e) {
    // One line naming the parallel file or a piece it named (the joined grid's own refusals
    // name it "<source> (N pieces): ", as a .pvtu's do).
    std::vector<std::string> prefixes = {std::string(kSource) + ": ", std::string(kSource) + " ("};
    for (const std::string& a : asked) prefixes.push_back(a + ": ");
    rayint::fuzz::check_line_starts(e.what(), prefixes);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::vector<std::string_view> parts = split(std::string_view(reinterpret_cast<const char*>(data), size));
  run(parts, [](std::string_view b, const rayint::PieceFileLoader& l) { return rayint::parse_pvts(b, kSource, l); });
  run(parts, [](std::string_view b, const rayint::PieceFileLoader& l) { return rayint::parse_pvtr(b, kSource, l); });
  return 0;
}
