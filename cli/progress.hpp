#pragma once
// Progress on stderr that rewrites one line (`\r`) only when stderr is a terminal; elsewhere (CI
// logs, files, pipes) it prints plain lines, one per tenth of the work, so a log never holds
// carriage returns. Every subcommand's -q/--quiet turns it off (add_quiet_flag).
#include <unistd.h>

#include <cstdio>
#include <mutex>
#include <string>

namespace rayint::cli {

// Whether a terminal progress line is open (written without its newline): main ends it before an
// error message, so the error is a line of its own.
inline bool& progress_line_open() {
  static bool open = false;
  return open;
}

inline bool stderr_is_terminal() {
  static const bool tty = ::isatty(STDERR_FILENO) != 0;
  return tty;
}

class ProgressLine {
 public:
  // `fraction` in [0, 1]; safe to call from several threads.
  void update(const std::string& text, double fraction) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (stderr_is_terminal()) {
      std::fprintf(stderr, "\r%s", text.c_str());
      open_ = true;
      progress_line_open() = true;
    } else {
      const int tenth = static_cast<int>(fraction * 10.0);
      if (tenth == last_tenth_) return;
      last_tenth_ = tenth;
      std::fprintf(stderr, "%s\n", text.c_str());
    }
    std::fflush(stderr);
  }
  // Ends the line on a terminal (nothing to do elsewhere).
  void finish() {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (open_) std::fputc('\n', stderr);
    open_ = false;
    progress_line_open() = false;
    std::fflush(stderr);
  }

 private:
  std::mutex mutex_;
  int last_tenth_ = -1;
  bool open_ = false;
};

}  // namespace rayint::cli
