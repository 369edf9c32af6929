#pragma once
// `--shard I/N` and `rayint merge` in the CLI (README, "Shards and merge"; core/shard.hpp).
//
// A sharded subcommand, given --shard I/N, does shard I's part of the run and writes a shard
// file (-o) instead of its report: {"rayint_shard": 1, "command", "args", "fingerprint", "build",
// "shard": {"index", "count"}, "data"}. `args` are the run's arguments without --shard,
// -o/--output, --threads and -q/--quiet (those do not change a figure); the fingerprint hashes
// the rayint version and build id (build_id), the command, those arguments and the bytes of the run's input files (every
// file the readers opened: the case or scene and the mesh, grid and preset files it names).
// `rayint merge` checks the shards belong together, then runs the recorded command again in
// merge mode: the subcommand takes its figures from the shards' data instead of computing
// them, and writes its report (to merge's -o) through the same code as a single run.
#include <CLI/CLI.hpp>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "rayint/core/shard.hpp"
#include "rayint/input/json_source.hpp"
#include "rayint/input/shard_reader.hpp"

namespace rayint::cli {

struct ShardContext {
  enum class Mode { none, shard, merge } mode = Mode::none;
  std::vector<std::string> args;  // the process's arguments after the subcommand (main sets them)
  // merge: the shards' data, indexed by shard (null where a shard is missing: --allow-partial)
  std::vector<nlohmann::json> data;
  std::vector<std::string> files;  // merge: the shard file each came from (empty if missing)
  std::string fingerprint;         // merge: the shards' fingerprint
};
ShardContext& shard_context();

// Registers --shard I/N on a subcommand (the text lands in `text`).
CLI::Option* add_shard_option(CLI::App* cmd, std::string& text);

// The shard a subcommand runs: whole when `text` is empty; sets the context's mode. A shard
// needs `output` (-o FILE) for its shard file: refused here, before the work.
ShardSpec begin_shard(const std::string& text, const std::string& output);
bool merging();

// A run's input files: `named` (those on the command line) and then every file the readers opened
// under `log` (the meshes, grids and data files the named ones refer to), each once.
std::vector<std::string> run_inputs(std::vector<std::string> named, const json_source::InputFileLog& log);

// This executable's build id: a version-5 UUID of the version and the bytes of the running
// executable (/proc/self/exe), so two builds of one version are told apart.
const std::string& build_id();

// The run's fingerprint: the build id, the command, its canonical arguments and the bytes of `input_files`.
std::string run_fingerprint(const std::string& command, const std::vector<std::string>& input_files);

// Shard mode: writes the shard file atomically to `path` (required: -o).
void write_shard(const std::string& path, const std::string& command, const ShardSpec& shard,
                 const std::vector<std::string>& input_files, nlohmann::json data);

// Merge mode: checks the recorded fingerprint against the inputs as they are now.
void check_merge_inputs(const std::string& command, const std::vector<std::string>& input_files);

// Merge mode: shard `index` of the run (index / the number of shards).
ShardSpec merged_shard(std::size_t index);

// Merge mode: the shards' parts of the run, after check_merge_inputs(command, input_files): the
// data of each shard present, read by `read` (a PartReader of input/shard_reader.hpp, given the
// shard's file and the field "data"), then `check(index, part)` (what the shard must cover:
// check_shard_band, check_shard_cover, check_shard_count) before the next shard is read.
template <class Part, class Check>
std::vector<Part> merged_parts(const std::string& command,
                               const std::vector<std::string>& input_files, PartReader<Part>* read,
                               Check check) {
  check_merge_inputs(command, input_files);
  const ShardContext& c = shard_context();
  std::vector<Part> parts;
  for (std::size_t i = 0; i < c.data.size(); ++i) {
    if (c.data[i].is_null()) continue;
    parts.push_back(read(c.data[i], c.files[i], "data"));
    check(i, parts.back());
  }
  return parts;
}

// Merge mode: shard `index` of the run must hold exactly the band of `total` items that
// shard_range(total, index/count) gives it ([begin, end) as its data say): a hand-edited or
// foreign shard that leaves a row out or repeats one is refused with one line naming its file
// and `field` (e.g. "data.row_begin").
void check_shard_band(std::size_t index, std::size_t total, long begin, long end, const std::string& field);

// merged_parts' check for a part that holds a band of image rows: check_shard_band on its height,
// row_begin and row_end ("data.row_begin").
struct RowBandCheck {
  template <class Part>
  void operator()(std::size_t index, const Part& part) const {
    check_shard_band(index, static_cast<std::size_t>(part.height), part.row_begin, part.row_end, "data.row_begin");
  }
};
inline constexpr RowBandCheck check_row_band{};

// Merge mode: likewise, where the band [want_begin, want_end) is computed by the caller.
void check_shard_cover(std::size_t index, std::size_t want_begin, std::size_t want_end, long begin, long end,
                       const std::string& field, const std::string& of = "");

// Merge mode: shard `index` of the run must hold exactly `expected` items (samples, rays) where
// its data hold `got`: refused with one line naming its file and `field` otherwise.
void check_shard_count(std::size_t index, std::size_t expected, std::size_t got, const std::string& field);

// `rayint merge`; `build` registers every subcommand on a fresh app (to replay the run).
void set_merge_command(CLI::App& app, std::function<void(CLI::App&)> build);

}  // namespace rayint::cli
