#include "rayint/core/atomic_file.hpp"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <fcntl.h>
#include <mutex>
#include <stdexcept>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

namespace rayint {
namespace {

// --- the temporaries of this process, readable from a signal handler ---------------------
// Fixed slots of plain chars: a handler may only read memory that is never freed or moved.
// A slot is free (0), being filled (1: the handler skips it) or live (2: the handler unlinks
// it). 512 slots bound the outputs one command can have staged at once; paths are refused
// beyond 4095 bytes (PATH_MAX on Linux) before anything is written.
constexpr int kSlots = 512;
constexpr std::size_t kPathBytes = 4096;
char g_paths[kSlots][kPathBytes];
std::atomic<int> g_state[kSlots];

int claim_slot(const std::string& tmp) {
  if (tmp.size() >= kPathBytes)
    throw std::runtime_error(tmp.substr(0, 64) + "...: path too long (more than 4095 bytes)");
  for (int i = 0; i < kSlots; ++i) {
    int expected = 0;
    if (g_state[i].compare_exchange_strong(expected, 1)) {
      std::memcpy(g_paths[i], tmp.c_str(), tmp.size() + 1);
      g_state[i].store(2);  // live before the file exists: unlinking a missing file is harmless
      return i;
    }
  }
  throw std::runtime_error(tmp + ": more than 512 outputs staged at once");
}

void release_slot(int slot, bool remove_file) {
  if (remove_file) ::unlink(g_paths[slot]);
  g_state[slot].store(0);
}

extern "C" void remove_temporaries_and_reraise(int sig) {
  for (int i = 0; i < kSlots; ++i)
    if (g_state[i].load() == 2) ::unlink(g_paths[i]);
  ::raise(sig);  // SA_RESETHAND restored the default action: the process ends by `sig`
}

// --- where a path leads --------------------------------------------------------------------
struct Target {
  std::string path;  // after following symbolic links
  bool stream = false;  // a FIFO or character device: written in place, never replaced
};

std::string directory_of(const std::string& p) {
  const auto slash = p.find_last_of('/');
  if (slash == std::string::npos) return "";
  return p.substr(0, slash + 1);
}

Target resolve(const std::string& path) {
  Target t{path, false};
  for (int hops = 0; hops < 40; ++hops) {  // 40: Linux's own limit on a chain of links
    struct stat st {};
    if (::lstat(t.path.c_str(), &st) != 0) {
      if (errno == ENOENT) return t;  // a new file (or the missing end of a dangling link)
      throw std::runtime_error(path + ": cannot write file (" + std::strerror(errno) + ")");
    }
    if (S_ISLNK(st.st_mode)) {
      std::vector<char> buf(static_cast<std::size_t>(st.st_size > 0 ? st.st_size : 255) + 1);
      const ssize_t n = ::readlink(t.path.c_str(), buf.data(), buf.size() - 1);
      if (n < 0) throw std::runtime_error(path + ": cannot follow link (" + std::strerror(errno) + ")");
      const std::string link(buf.data(), static_cast<std::size_t>(n));
      t.path = (!link.empty() && link[0] == '/') ? link : directory_of(t.path) + link;
      continue;
    }
    if (S_ISREG(st.st_mode)) return t;
    if (S_ISFIFO(st.st_mode) || S_ISCHR(st.st_mode)) {
      t.stream = true;
      return t;
    }
    if (S_ISDIR(st.st_mode)) throw std::runtime_error(path + ": is a directory, not an output file");
    throw std::runtime_error(path + ": is a block device or socket, not an output file");
  }
  throw std::runtime_error(path + ": too many levels of symbolic links");
}

// --- checked writes ----------------------------------------------------------------------
// Writes all of `content` to `fd` and closes it; returns 0 or the errno of the first failure.
int write_and_close(int fd, const std::string& content) {
  const char* p = content.data();
  std::size_t left = content.size();
  int err = 0;
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      err = errno;
      break;
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  if (::close(fd) != 0 && err == 0) err = errno;  // NFS and quotas report at close
  return err;
}

[[noreturn]] void fail(const std::string& path, int err) {
  throw std::runtime_error(path + ": cannot write file (" + std::strerror(err) + ")");
}

void stream_into(const std::string& shown, const Target& t, const std::string& content) {
  const int fd = ::open(t.path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) fail(shown, errno);
  if (const int err = write_and_close(fd, content)) fail(shown, err);
}

std::atomic<unsigned> g_counter{0};

// Writes `content` to a new temporary beside the target; returns its slot.
int write_temporary(const std::string& shown, const Target& t, const std::string& content) {
  const std::string tmp = t.path + ".tmp." + std::to_string(::getpid()) + "." +
                          std::to_string(g_counter.fetch_add(1));
  const int slot = claim_slot(tmp);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) {
    const int err = errno;
    release_slot(slot, false);
    fail(shown, err);
  }
  if (const int err = write_and_close(fd, content)) {
    release_slot(slot, true);
    fail(shown, err);
  }
  return slot;
}

void rename_onto(const std::string& shown, int slot, const std::string& target) {
  if (::rename(g_paths[slot], target.c_str()) != 0) {
    const int err = errno;
    release_slot(slot, true);
    fail(shown, err);
  }
  release_slot(slot, false);
}

// --- the batch ------------------------------------------------------------------------------
struct Staged {
  std::string shown;   // the path as the user gave it, for messages
  Target target;
  int slot = -1;       // the temporary (regular targets)
  std::string memory;  // the content (streamed targets)
};

std::mutex g_batch_mutex;
bool g_batch_open = false;
std::vector<Staged> g_staged;

void discard_staged() {
  for (auto& s : g_staged)
    if (s.slot >= 0) release_slot(s.slot, true);
  g_staged.clear();
}

}  // namespace

void write_file_atomically(const std::string& path, const std::string& content) {
  const Target t = resolve(path);
  std::unique_lock<std::mutex> lock(g_batch_mutex);
  if (g_batch_open) {
    Staged s{path, t, -1, {}};
    if (t.stream)
      s.memory = content;
    else
      s.slot = write_temporary(path, t, content);
    g_staged.push_back(std::move(s));
    return;
  }
  lock.unlock();
  if (t.stream) {
    stream_into(path, t, content);
    return;
  }
  rename_onto(path, write_temporary(path, t, content), t.path);
}

OutputBatch::OutputBatch() {
  std::lock_guard<std::mutex> lock(g_batch_mutex);
  if (g_batch_open) throw std::logic_error("OutputBatch: one batch at a time");
  g_batch_open = true;
}

OutputBatch::~OutputBatch() {
  std::lock_guard<std::mutex> lock(g_batch_mutex);
  discard_staged();
  g_batch_open = false;
}

void OutputBatch::commit() {
  std::lock_guard<std::mutex> lock(g_batch_mutex);
  // Renames first (they cannot run out of space), streams last: a FIFO reader blocks us.
  for (auto& s : g_staged) {
    if (s.slot < 0) continue;
    const int slot = s.slot;
    s.slot = -1;
    try {
      rename_onto(s.shown, slot, s.target.path);
    } catch (...) {
      discard_staged();
      throw;
    }
  }
  std::vector<Staged> streams;
  streams.swap(g_staged);
  for (const auto& s : streams)
    if (s.target.stream) stream_into(s.shown, s.target, s.memory);
}

void remove_temporaries_on_signals() {
  for (const int sig : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction old {};
    if (::sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN)
      continue;  // ignored by whoever started us (nohup, a background job): keep it so
    struct sigaction sa {};
    sa.sa_handler = remove_temporaries_and_reraise;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESETHAND;
    ::sigaction(sig, &sa, nullptr);
  }
}

}  // namespace rayint
