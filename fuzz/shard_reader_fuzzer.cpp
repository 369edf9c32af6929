// libFuzzer target for the shard-data readers of `rayint merge` (input/shard_reader.hpp) on
// arbitrary bytes parsed as JSON, followed by what the merge does with what they accept
// (finish a Monte Carlo tree, assemble a mesh render or an own-mode cell render, a scatter
// comparison, a cells report).
// Seeds: fuzz/seeds/shard/ (the data of small shard files of every kind). Run it with
// `RAYINT_FUZZ_TARGET=shard_reader scripts/fuzz.sh`. A finding is any of:
//   - a crash, sanitizer report, hang or leak;
//   - an exception other than rayint::InputError (readers) or std::invalid_argument (the
//     merge's consistency checks) escaping;
//   - an InputError whose message is not one line starting with "<source>: ".
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

#include "rayint/input/json_source.hpp"
#include "rayint/input/shard_reader.hpp"
#include "fuzz_checks.hpp"

namespace {

constexpr const char* kSource = "fuzz-shard.json";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  nlohmann::json j;
  try {
    j = rayint::json_source::parse(text, kSource);
  } catch (const rayint::InputError& e) {
    rayint::fuzz::check_message(e.what(), kSource);
    return 0;
  }
  using rayint::fuzz::merge_refusals_are_one_line;
  using rayint::fuzz::refusals_are_one_line;
  refusals_are_one_line(kSource, [&] {
    const rayint::MonteCarloPart p = rayint::monte_carlo_part_from_json(j, kSource, "data");
    if (p.blocks < (1u << 20)) {
      rayint::BlockSumTree tree(p.blocks);
      for (const auto& [key, sums] : p.nodes) tree.insert(key.first, key.second, sums);
      tree.reduce();
      (void)tree.total(p.scores);
    }
  });
  refusals_are_one_line(kSource, [&] { (void)rayint::stress_partial_from_json(j, kSource, "data"); });
  merge_refusals_are_one_line(kSource, [&] {
    const rayint::MeshRenderPart p = rayint::mesh_render_part_from_json(j, kSource, "data");
    (void)rayint::assemble_mesh_render({p});
  });
  merge_refusals_are_one_line(kSource, [&] {
    const rayint::CellMeshRenderPart p = rayint::cell_mesh_render_part_from_json(j, kSource, "data");
    (void)rayint::assemble_cell_mesh_render({p});
  });
  refusals_are_one_line(kSource, [&] { (void)rayint::sweep_part_from_json(j, kSource, "data"); });
  merge_refusals_are_one_line(kSource, [&] {
    const rayint::VolumeComparisonPart p = rayint::volume_comparison_part_from_json(j, kSource, "data");
    if (static_cast<long long>(p.width) * p.height <= (1 << 16)) (void)rayint::finish_volume_comparison({p});
  });
  return merge_refusals_are_one_line(kSource, [&] {
    const rayint::CellsSamples p = rayint::cells_samples_from_json(j, kSource, "data");
    rayint::CellsStudyOptions o;
    o.levels = {1, 2};
    o.voxel_sizes = {4};
    (void)rayint::finish_cells_study(o, {p});
  });
}
