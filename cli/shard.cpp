// --shard I/N and `rayint merge` (shard.hpp).
#include "shard.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <iostream>
#include <limits>
#include <map>
#include <stdexcept>

#include "commands.hpp"
#include "rayint/core/atomic_file.hpp"
#include "rayint/core/error.hpp"
#include "rayint/core/limits.hpp"
#include "rayint/input/json_source.hpp"

namespace rayint::cli {
namespace {

constexpr int kShardFormat = 1;

// The run's arguments without the shard, the output and -q/--quiet (`args` of a shard file);
// for the fingerprint also without --threads, which changes no figure.
std::vector<std::string> canonical_args(const std::vector<std::string>& args, bool keep_threads) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--shard" || a == "-o" || a == "--output" || (a == "--threads" && !keep_threads)) {
      ++i;  // and its value
      continue;
    }
    if (a.rfind("--shard=", 0) == 0 || a.rfind("--output=", 0) == 0 ||
        (a.rfind("--threads=", 0) == 0 && !keep_threads) ||
        (a.rfind("-o", 0) == 0 && a.size() > 2 && a[2] != '-') || a == "-q" || a == "--quiet")
      continue;
    out.push_back(a);
  }
  return out;
}

std::string file_bytes(const std::string& path) {
  return json_source::read_file_bytes(path, [&](const std::string& reason) {
    throw InputError(path + ": cannot read file (" + reason + ")");
  });
}

struct ShardFile {
  std::string path, command, fingerprint, build;
  std::vector<std::string> args;
  ShardSpec shard;
  nlohmann::json data;
};

ShardFile read_shard_file(const std::string& path) {
  const nlohmann::json j = json_source::parse(json_source::read_text_file(path), path);
  ShardFile f;
  f.path = path;
  if (!j.is_object() || !j.contains("rayint_shard"))
    field::fail(path, "rayint_shard", "missing: not a shard file (written by a command run with --shard I/N)");
  if (j["rayint_shard"] != kShardFormat)
    field::fail(path, "rayint_shard", "unsupported shard format (expected " + std::to_string(kShardFormat) + ")");
  for (const char* key : {"command", "fingerprint"})
    if (!j.contains(key) || !j[key].is_string()) field::fail(path, key, "must be a string");
  f.command = j["command"];
  f.fingerprint = j["fingerprint"];
  if (!j.contains("build") || !j["build"].is_string()) field::fail(path, "build", "must be a string (the build id of the rayint that wrote it)");
  f.build = j["build"];
  if (!j.contains("args") || !j["args"].is_array()) field::fail(path, "args", "must be an array of strings");
  for (std::size_t i = 0; i < j["args"].size(); ++i) {
    if (!j["args"][i].is_string()) field::fail(path, field::index_path("args", i), "must be a string");
    f.args.push_back(j["args"][i]);
  }
  const nlohmann::json* s = j.contains("shard") ? &j["shard"] : nullptr;
  if (!s || !s->is_object() || !s->contains("index") || !s->contains("count") ||
      !(*s)["index"].is_number_integer() || !(*s)["count"].is_number_integer())
    field::fail(path, "shard", "must be {\"index\": I, \"count\": N}");
  f.shard.index = (*s)["index"];
  f.shard.count = (*s)["count"];
  if (f.shard.count < 1 || f.shard.index < 0 || f.shard.index >= f.shard.count)
    field::fail(path, "shard", "needs 0 <= index < count");
  limits::check(limits::kShards, static_cast<double>(f.shard.count), path + ": shard.count");
  if (!j.contains("data")) field::fail(path, "data", "missing");
  f.data = j["data"];
  return f;
}

}  // namespace

ShardContext& shard_context() {
  static ShardContext context;
  return context;
}

CLI::Option* add_shard_option(CLI::App* cmd, std::string& text) {
  return cmd->add_option("--shard", text,
                         "I/N: do shard I of N of this run (same seed and count) and write a shard "
                         "file to -o; `rayint merge` joins the shards into the run's report");
}

namespace {
void require_shard_file(const std::string& path) {
  if (path.empty() || path == "-") throw std::invalid_argument("--shard: needs -o FILE for the shard file");
}
}  // namespace

ShardSpec begin_shard(const std::string& text, const std::string& output) {
  if (text.empty()) return {};
  if (merging()) throw std::invalid_argument("--shard: not in a merge");
  const ShardSpec s = parse_shard(text);
  limits::check(limits::kShards, static_cast<double>(s.count), "--shard " + text);
  require_shard_file(output);
  shard_context().mode = ShardContext::Mode::shard;
  return s;
}

bool merging() { return shard_context().mode == ShardContext::Mode::merge; }

std::vector<std::string> run_inputs(std::vector<std::string> named, const json_source::InputFileLog& log) {
  for (const auto& f : log.files())
    if (std::find(named.begin(), named.end(), f) == named.end()) named.push_back(f);
  return named;
}

const std::string& build_id() {
  // The executable's own bytes, hashed once (a 20-30 MB file: ~0.1 s, once per shard or merge).
  // Two builds of one version -- another commit, a local change, another compiler or flags --
  // are different files; the same build copied or installed elsewhere is the same file. A
  // hash of the sources at configure time would miss a change made after configuring, and git
  // describe a change not committed; the executable is what computed the figures.
  static const std::string id = [] {
    std::ifstream in("/proc/self/exe", std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in.good() && !in.eof()) throw std::runtime_error("cannot read /proc/self/exe for the build id");
    return fingerprint({"rayint-build", std::string("rayint ") + RAYINT_VERSION, bytes});
  }();
  return id;
}

std::string run_fingerprint(const std::string& command, const std::vector<std::string>& input_files) {
  // The version and the build too: shards of two rayint builds are not one run, even where the
  // figures agree.
  std::vector<std::string> parts{"rayint-run", std::string("rayint ") + RAYINT_VERSION, build_id(), command};
  for (const auto& a : canonical_args(shard_context().args, false)) parts.push_back(a);
  parts.push_back("inputs");
  for (const auto& f : input_files) parts.push_back(file_bytes(f));
  return fingerprint(parts);
}

void write_shard(const std::string& path, const std::string& command, const ShardSpec& shard,
                 const std::vector<std::string>& input_files, nlohmann::json data) {
  require_shard_file(path);
  nlohmann::json j;
  j["rayint_shard"] = kShardFormat;
  j["command"] = command;
  j["args"] = canonical_args(shard_context().args, true);
  j["fingerprint"] = run_fingerprint(command, input_files);
  j["build"] = build_id();
  j["shard"] = {{"index", shard.index}, {"count", shard.count}};
  j["data"] = std::move(data);
  write_file_atomically(path, j.dump() + "\n");
}

void check_merge_inputs(const std::string& command, const std::vector<std::string>& input_files) {
  const std::string now = run_fingerprint(command, input_files);
  if (now != shard_context().fingerprint)
    throw std::invalid_argument("merge: the run's input files changed since the shards ran (fingerprint " +
                                now + ", shards " + shard_context().fingerprint + ")");
}

ShardSpec merged_shard(std::size_t index) {
  return ShardSpec{static_cast<long>(index), static_cast<long>(shard_context().data.size())};
}

void check_shard_band(std::size_t index, std::size_t total, long begin, long end, const std::string& field) {
  const IndexRange want = shard_range(total, merged_shard(index));
  check_shard_cover(index, want.begin, want.end, begin, end, field, " of " + std::to_string(total));
}

void check_shard_cover(std::size_t index, std::size_t want_begin, std::size_t want_end, long begin, long end,
                       const std::string& field, const std::string& of) {
  const ShardContext& c = shard_context();
  const ShardSpec spec = merged_shard(index);
  if (want_begin == want_end && begin == end) return;  // an empty band (more shards than items)
  if (begin != static_cast<long>(want_begin) || end != static_cast<long>(want_end))
    throw InputError(c.files[index] + ": " + field + ": shard " + spec.label() + of + " must cover [" +
                     std::to_string(want_begin) + ", " + std::to_string(want_end) + "), but covers [" +
                     std::to_string(begin) + ", " + std::to_string(end) + ")");
}

void check_shard_count(std::size_t index, std::size_t expected, std::size_t got, const std::string& field) {
  if (expected == got) return;
  const ShardContext& c = shard_context();
  const ShardSpec spec = merged_shard(index);
  throw InputError(c.files[index] + ": " + field + ": shard " + spec.label() + " of this run covers " +
                   std::to_string(expected) + ", but its data hold " + std::to_string(got) +
                   " (a gap or an overlap: a shard of another run, or edited)");
}

void set_merge_command(CLI::App& app, std::function<void(CLI::App&)> build) {
  struct Options {
    std::vector<std::string> shards;
    std::string output;
    bool allow_partial = false;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "merge", "Join the shard files of one run (--shard I/N) into the report the single run writes");
  cmd->add_option("shards", opt->shards, "shard files")->required();
  cmd->add_option("-o,--output", opt->output, "the merged report (or image) to write")->required();
  cmd->add_flag("--allow-partial", opt->allow_partial,
                "merge the shards present even if some are missing, and say what they cover");
  cmd->callback([opt, build] {
    std::vector<ShardFile> files;
    for (const auto& p : opt->shards) files.push_back(read_shard_file(p));
    const ShardFile& first = files.front();
    std::map<long, const ShardFile*> by_index;
    for (const ShardFile& f : files) {
      if (f.build != build_id())
        throw InputError(f.path + ": build: written by another rayint build (" + f.build + "; this rayint " +
                         RAYINT_VERSION + " is build " + build_id() + "): shards and merge run one build");
      if (f.fingerprint != first.fingerprint || f.command != first.command || f.shard.count != first.shard.count)
        throw InputError(f.path + ": fingerprint: a shard of a different run (" + f.fingerprint + " " +
                         f.command + " " + f.shard.label() + ", but " + first.path + " is " +
                         first.fingerprint + " " + first.command + " " + first.shard.label() + ")");
      const auto [it, fresh] = by_index.emplace(f.shard.index, &f);
      if (!fresh)
        throw InputError(f.path + ": shard: duplicate of shard " + f.shard.label() + " (also " +
                         it->second->path + ")");
    }
    const long count = first.shard.count;
    std::string missing;
    for (long i = 0; i < count; ++i)
      if (!by_index.count(i)) missing += (missing.empty() ? "" : ", ") + ShardSpec{i, count}.label();
    if (!missing.empty() && !opt->allow_partial)
      throw InputError("merge: missing shard " + missing + " of run " + first.fingerprint +
                       " (--allow-partial merges the shards present)");
    ShardContext& c = shard_context();
    c.mode = ShardContext::Mode::merge;
    c.fingerprint = first.fingerprint;
    c.data.assign(static_cast<std::size_t>(count), nlohmann::json());
    c.files.assign(static_cast<std::size_t>(count), std::string());
    for (const auto& [i, f] : by_index) {
      c.data[static_cast<std::size_t>(i)] = f->data;
      c.files[static_cast<std::size_t>(i)] = f->path;
    }
    c.args = first.args;
    // Replay the run: the same subcommand and arguments, its output to merge's -o.
    CLI::App replay{"rayint"};
    replay.require_subcommand(1);
    build(replay);
    std::vector<std::string> argv{first.command};
    for (const auto& a : first.args) argv.push_back(a);
    argv.push_back("-o");
    argv.push_back(opt->output);
    argv.push_back("--quiet");
    std::reverse(argv.begin(), argv.end());  // CLI11 parses a reversed vector
    // The note after the replay: a merge that fails prints its error alone, not after this note.
    const auto note_partial = [&] {
      if (!missing.empty())
        std::cerr << "rayint merge: partial: " << by_index.size() << " of " << count
                  << " shards (missing " << missing << "); the report covers only their part of the run\n";
    };
    try {
      replay.parse(argv);
    } catch (const ChecksFailed&) {  // the report is written (exit 1): the note applies
      note_partial();
      throw;
    }
    note_partial();
  });
}

}  // namespace rayint::cli
