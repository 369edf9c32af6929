// libFuzzer target for rayint's .vtu reader (rayint::parse_vtu, input/vtk_xml_reader.hpp) on
// arbitrary bytes. Built by fuzz/CMakeLists.txt with -fsanitize=fuzzer,address,undefined; run it
// with RAYINT_FUZZ_TARGET=vtu_reader scripts/fuzz.sh (seeds: tests/fixtures/vtkxml/*.vtu, every
// data mode / encoding / compressor / header type / byte order VTK writes). A finding is any of:
//   - a crash, sanitizer report, hang, leak or out-of-memory;
//   - an exception other than rayint::InputError escaping the reader;
//   - an InputError whose message is not one line starting with "<source>: ";
//   - a mesh accepted although it breaks the reader's guarantees: one finite scalar per point,
//     finite points, at least one tet, every index in range.
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

constexpr const char* kSource = "fuzz-input.vtu";

void check_mesh(const rayint::TetMesh& m) {
  require(!m.tets.empty() && m.scalars.size() == m.points.size());
  for (const auto& p : m.points) require(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]));
  for (double s : m.scalars) require(std::isfinite(s));
  for (const auto& t : m.tets)
    for (std::int32_t i : t) require(i >= 0 && static_cast<std::size_t>(i) < m.points.size());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  return rayint::fuzz::refusals_are_one_line(kSource, [&] {
    check_mesh(rayint::parse_vtu(bytes, kSource));
  });
}
