#pragma once
// Progress on stderr that rewrites one line (`\r`) only when stderr is a terminal; elsewhere (CI
// logs, files, pipes) it prints plain lines, one per tenth of the work, so a log never holds
// carriage returns. Every subcommand's -q/--quiet turns it off (add_quiet_flag).
#include <unistd.h>

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>
#include <utility>

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

// A stage without a measure of its own progress (reading a mesh, building the traversal): silent
// when it ends within a second; past a second, one line "<label> ..." then, at its end,
// "<label>: <summary> (<seconds> s)" (issue 33: a 10M-tet mesh takes tens of seconds to load).
class SlowStage {
 public:
  SlowStage(std::string label, bool quiet) : label_(std::move(label)), start_(std::chrono::steady_clock::now()) {
    if (quiet) return;
    watcher_ = std::thread([this] {
      std::unique_lock<std::mutex> lock(mutex_);
      if (cv_.wait_for(lock, std::chrono::seconds(1), [this] { return ended_; })) return;
      std::fprintf(stderr, "%s ...\n", label_.c_str());
      std::fflush(stderr);
      announced_ = true;
    });
  }
  ~SlowStage() { stop(); }
  SlowStage(const SlowStage&) = delete;
  SlowStage& operator=(const SlowStage&) = delete;
  // Ends the stage; prints the summary when the stage was announced.
  void done(const std::string& summary) {
    stop();
    if (!announced_) return;
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    std::fprintf(stderr, "%s: %s (%.1f s)\n", label_.c_str(), summary.c_str(), s);
    std::fflush(stderr);
  }

 private:
  void stop() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      ended_ = true;
    }
    cv_.notify_all();
    if (watcher_.joinable()) watcher_.join();
  }
  std::string label_;
  std::chrono::steady_clock::time_point start_;
  std::mutex mutex_;
  std::condition_variable cv_;
  bool ended_ = false;
  bool announced_ = false;  // written by the watcher, read after join
  std::thread watcher_;
};

}  // namespace rayint::cli
