#pragma once
// Output files that are never half-written, never replace what they should not, and never
// outlive an interrupted run as temporaries.
//
// Where `path` leads (write_file_atomically):
//   - a regular file or nothing: the content goes to a temporary file beside the target
//     (`<target>.tmp.<pid>.<n>`) and is renamed onto it, so a reader sees the old file or the
//     new one, never a part;
//   - a symbolic link: the link is followed (chains too) and its target is written as above;
//     the link stays a link;
//   - a FIFO or a character device (`/dev/null`, `/dev/stdout`, a named pipe): the content is
//     streamed into it, since such a file cannot be replaced atomically and must not be
//     replaced by a regular file;
//   - a directory, a block device or a socket: refused with one line naming the path.
// Every write and the final close are checked; a failure (a full disk, a quota) removes the
// temporary file and throws std::runtime_error naming the path and the reason.
#include <string>

namespace rayint {

void write_file_atomically(const std::string& path, const std::string& content);

// While an OutputBatch is alive, write_file_atomically writes each output to its temporary
// file (or, for a FIFO or device, keeps it in memory) and commit() renames them all onto their
// targets at the end. A batch destroyed without commit() removes its temporaries: a command
// that fails half-way, or a full disk during any one output, leaves every earlier file as it
// was. One batch at a time (the CLI makes one per command); without a batch every call
// writes at once, as described above.
class OutputBatch {
 public:
  OutputBatch();
  ~OutputBatch();
  OutputBatch(const OutputBatch&) = delete;
  OutputBatch& operator=(const OutputBatch&) = delete;
  // Renames every staged output onto its target (and streams the in-memory ones). Throws
  // std::runtime_error naming the first target that could not be written; the outputs not
  // yet renamed are then removed.
  void commit();
};

// Installs handlers for SIGINT, SIGTERM and SIGHUP that remove every temporary output file
// of this process and then end it by the same signal (the handler is reset on entry, so a
// second signal stops the process at once). Call once, early in main.
void remove_temporaries_on_signals();

}  // namespace rayint
