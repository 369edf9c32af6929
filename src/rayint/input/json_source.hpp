#pragma once
// JSON input with field paths: the one place where rayint's input files (cases, candidates,
// gate configs, scenes, grids, slab scenes and benchmarks) are parsed into nlohmann::json, so
// that every problem can be reported as one line `<source>: <field path>: <what>` (InputError).
// Duplicate keys, which nlohmann's DOM parser silently resolves to the last one, and numbers that
// overflow a double (1e999, nlohmann's out_of_range.406) are reported at their field; syntax
// errors carry the 1-based line and column of the offending character and nlohmann's reason.
// Parsing is strict: no comments, nothing but whitespace after the document.
#include <cstddef>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "rayint/core/error.hpp"
#include "rayint/core/format.hpp"

namespace rayint::json_source {

nlohmann::json parse(std::string_view text, const std::string& source);

// Streaming the elements of one array pattern instead of keeping them in the tree, so that a
// file whose bulk is one long array (a case of millions of segments) is read in memory close to
// the size of what the caller keeps rather than nlohmann's DOM (~10x the text). The arrays at
// `array_path` -- field names and "[]" for any array index, e.g. {"rays", "[]", "segments"} for
// rays[i].segments of the root object -- are left in the tree empty, and each of their elements
// is handed to element(value, indices) as soon as it is complete, then dropped; `indices` are the
// array indices along its path (rays[3].segments[7]: {3, 7}). Everything else -- duplicate keys,
// overflowing numbers, syntax errors, and their messages -- is exactly as parse. An exception
// thrown by `element` ends the parse and propagates.
struct StreamedArray {
  std::vector<std::string> array_path;
  std::function<void(nlohmann::json& element, const std::vector<std::size_t>& indices)> element;
};
nlohmann::json parse(std::string_view text, const std::string& source, const StreamedArray& streamed);
// The same, keeping each object's keys in file order (for formats whose order means something:
// a gate config's checks are run and reported in the order it lists them).
nlohmann::ordered_json parse_ordered(std::string_view text, const std::string& source);

// Limits on what an input may cost (docs/limits.md): JSON nesting depth, and the bytes of one
// input file (any format), which RAYINT_MAX_INPUT_BYTES overrides. 4 GiB holds the largest
// inputs measured (a 10M-tet binary .vtu is ~0.6 GB, an ASCII legacy .vtk of it ~1.5 GB) with room.
inline constexpr std::size_t kMaxJsonDepth = 256;
inline constexpr std::size_t kDefaultMaxInputBytes = std::size_t{4} << 30;
// The limit in force: RAYINT_MAX_INPUT_BYTES if set (InputError if it is not a whole number
// >= 1), else kDefaultMaxInputBytes.
std::size_t max_input_bytes();

// The whole file as text; InputError "<path>: cannot read file (<reason>)".
std::string read_text_file(const std::string& path);

// While alive, records the path of every file read_file_bytes (and so read_text_file and every
// reader built on them) opens on this thread, in order, each once: the files a run's result
// depends on, a case and the meshes or grids it names, which shard fingerprints hash
// (cli/shard.hpp). Logs nest; the innermost records.
class InputFileLog {
 public:
  InputFileLog();
  ~InputFileLog();
  InputFileLog(const InputFileLog&) = delete;
  InputFileLog& operator=(const InputFileLog&) = delete;
  const std::vector<std::string>& files() const { return files_; }
  static void note(const std::string& path);  // by the readers: adds path to the active log, if any

 private:
  std::vector<std::string> files_;
  InputFileLog* outer_;
};
// The whole file's bytes; when it cannot be opened or read, fail(reason), reason strerror(errno)
// or "read error"; fail must throw. A directory or a device is refused; a FIFO or /dev/stdin is
// read as a stream; a file (or stream) larger than max_input_bytes() is refused, a regular file
// before any byte is read.
std::string read_file_bytes(const std::string& file,
                            const std::function<void(const std::string& reason)>& fail);

// A file's bytes for a reader that only looks at them (the mesh readers: a mesh file of 3-600 MB).
// A regular file of at least 1 MiB is mapped read-only with MAP_POPULATE: the page cache's own
// pages, entered in one mmap call, neither copied nor zeroed (read_file_bytes copies the file
// twice, through a 64 KiB buffer into a fresh string whose pages the kernel zeroes and faults in
// one by one: 750-1,200 faults on the 105k-tet meshes, ~5-8 ms of system time on the Zen 5 VM,
// issue 33). Smaller files, directories, devices, FIFOs and files over the input limit go through
// read_file_bytes, with its checks and messages. A mapped file truncated by another process
// while it is read would end the process with SIGBUS instead of an error line (a file replaced
// by rename, as editors and writers do, is not affected: the mapping keeps the old one).
class FileBytes {
 public:
  FileBytes() = default;
  explicit FileBytes(std::string text) : text_(std::move(text)) {}
  FileBytes(FileBytes&& o) noexcept;
  FileBytes& operator=(FileBytes&& o) noexcept;
  FileBytes(const FileBytes&) = delete;
  FileBytes& operator=(const FileBytes&) = delete;
  ~FileBytes();
  std::string_view view() const { return mapped_ != nullptr ? std::string_view(mapped_, size_) : std::string_view(text_); }
  operator std::string_view() const { return view(); }  // NOLINT: read like the string it replaces

 private:
  friend FileBytes read_file_bytes_mapped(const std::string&, const std::function<void(const std::string&)>&);
  char* mapped_ = nullptr;
  std::size_t size_ = 0;
  std::string text_;
};
FileBytes read_file_bytes_mapped(const std::string& file, const std::function<void(const std::string& reason)>& fail);
// read_file_bytes_mapped with read_text_file's message.
FileBytes read_big_file(const std::string& path);

// The message helpers (core/error.hpp, core/format.hpp), named here for the readers' schema walks.
using field::fail;
using field::index_path;
using field::member_path;
using field::one_line;
using field::quoted;
using rayint::format_number;

}  // namespace rayint::json_source
