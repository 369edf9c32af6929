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
#include <vector>

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

// Lines about reading the input (a slow stage's time, what a mode will do) are held until the
// input has passed its checks: the computation's first progress update prints them, or the end of
// a command that succeeded (main). A bad input's error is then the only line on stderr, however
// long the reading took ("one line, once", issue 30).
class HeldLines {
 public:
  static HeldLines& instance() {
    static HeldLines held;
    return held;
  }
  void hold(std::string line) {
    const std::lock_guard<std::mutex> lock(mutex_);
    lines_.push_back(std::move(line));
  }
  void release() {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (const std::string& line : lines_) std::fprintf(stderr, "%s\n", line.c_str());
    if (!lines_.empty()) std::fflush(stderr);
    lines_.clear();
  }

 private:
  std::mutex mutex_;
  std::vector<std::string> lines_;
};

class ProgressLine {
 public:
  // `fraction` in [0, 1]; safe to call from several threads.
  void update(const std::string& text, double fraction) {
    HeldLines::instance().release();  // the input was accepted: the computation has begun
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
// when it ends within a second. Past a second, on a terminal, an open line "<label> ..." (erased
// when the stage ends, by success or by an error); at its end, held (HeldLines) until the input is
// accepted, "<label>: <summary> (<seconds> s)" (issue 33: a 10M-tet mesh takes tens of seconds to
// load). In a log only the held line is written, so a log never holds a stage without its end.
class SlowStage {
 public:
  SlowStage(std::string label, bool quiet) : label_(std::move(label)), start_(std::chrono::steady_clock::now()) {
    if (quiet) return;
    watcher_ = std::thread([this] {
      std::unique_lock<std::mutex> lock(mutex_);
      if (cv_.wait_for(lock, std::chrono::seconds(1), [this] { return ended_; })) return;
      announced_ = true;
      if (!stderr_is_terminal()) return;
      std::fprintf(stderr, "\r%s ...", label_.c_str());
      std::fflush(stderr);
      line_open_ = true;
      progress_line_open() = true;
    });
  }
  ~SlowStage() { stop(); }
  SlowStage(const SlowStage&) = delete;
  SlowStage& operator=(const SlowStage&) = delete;
  // Ends the stage; holds the summary when the stage took over a second.
  void done(const std::string& summary) {
    stop();
    if (!announced_) return;
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, " (%.1f s)", s);
    HeldLines::instance().hold(label_ + ": " + summary + seconds);
  }

 private:
  // Joins the watcher and erases its open terminal line.
  void stop() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      ended_ = true;
    }
    cv_.notify_all();
    if (watcher_.joinable()) watcher_.join();
    if (line_open_) {
      std::fputs("\r\033[K", stderr);
      std::fflush(stderr);
      line_open_ = false;
      progress_line_open() = false;
    }
  }
  std::string label_;
  std::chrono::steady_clock::time_point start_;
  std::mutex mutex_;
  std::condition_variable cv_;
  bool ended_ = false;
  bool announced_ = false;  // written by the watcher, read after join
  bool line_open_ = false;  // the same: the terminal line "<label> ..." is on screen
  std::thread watcher_;
};

}  // namespace rayint::cli
