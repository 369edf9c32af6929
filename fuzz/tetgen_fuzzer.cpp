// libFuzzer target for the TetGen reader (rayint::parse_tetgen, input/tetgen_reader.hpp) on
// arbitrary bytes: the input is the .node text, a line "===", and the .ele text (no "===": the
// .ele is empty). An accepted mesh is repaired and traversed (mesh_fuzz_checks.hpp). Run it with
// `RAYINT_FUZZ_TARGET=tetgen scripts/fuzz.sh`. Findings as in vtk_legacy_fuzzer.cpp; a message
// must name the .node or the .ele file.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "mesh_fuzz_checks.hpp"
#include "rayint/input/tetgen_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const std::size_t split = bytes.find("\n===\n");
  const std::string_view node = bytes.substr(0, split);
  const std::string_view ele = split == std::string_view::npos ? std::string_view() : bytes.substr(split + 5);
  return rayint::fuzz::refusals_start_with({"fuzz.node: ", "fuzz.ele: "}, [&] {
    rayint::fuzz::check_mesh(rayint::parse_tetgen(node, "fuzz.node", ele, "fuzz.ele"), "fuzz.ele");
  });
}
