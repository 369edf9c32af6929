#include "rayint/input/json_source.hpp"

#include "rayint/core/limits.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <cstdlib>
#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>
#include <sys/stat.h>
#include <type_traits>
#include <utility>
#include <vector>

namespace rayint::json_source {

namespace {

// ---------------------------------------------------------------------------------------------
// Stage 1: SAX builder with field paths. `Json` is nlohmann::json (keys sorted) or
// nlohmann::ordered_json (keys in file order); both keep their elements where they are while a
// nested value is filled (objects and arrays only grow at the end of the innermost container).

template <class Json>
class PathTrackingBuilder final : public Json::json_sax_t {
 public:
  using json = Json;
  using typename Json::json_sax_t::number_integer_t;
  using typename Json::json_sax_t::number_unsigned_t;
  using typename Json::json_sax_t::number_float_t;
  using typename Json::json_sax_t::string_t;
  using typename Json::json_sax_t::binary_t;

  PathTrackingBuilder(std::string_view text, const std::string& source,
                      const StreamedArray* streamed = nullptr)
      : text_(text), source_(source), streamed_(streamed) {}

  json take_root() { return std::move(root_); }

  bool null() override { return add(json(nullptr)); }
  bool boolean(bool val) override { return add(json(val)); }
  bool number_integer(number_integer_t val) override { return add(json(val)); }
  bool number_unsigned(number_unsigned_t val) override { return add(json(val)); }
  bool number_float(number_float_t val, const string_t& /*token*/) override {
    return add(json(val));
  }
  bool string(string_t& val) override { return add(json(std::move(val))); }
  bool binary(binary_t& val) override { return add(json(std::move(val))); }

  bool start_object(std::size_t /*elements*/) override {
    check_depth();
    open(json(json::value_t::object), false);
    return true;
  }
  bool key(string_t& val) override {
    frames_.back().key = val;
    json& object = *frames_.back().container;
    if (object.contains(val)) fail(source_, path(), "duplicate field");
    member_ = &object[val];
    return true;
  }
  bool end_object() override { return close(); }
  bool start_array(std::size_t /*elements*/) override {
    check_depth();
    const bool streams = streamed_ != nullptr && at_streamed_path();
    open(json(json::value_t::array), true);
    frames_.back().streamed = streams;
    return true;
  }
  bool end_array() override { return close(); }

  bool parse_error(std::size_t position, const std::string& last_token,
                   const typename Json::exception& ex) override {
    // out_of_range.406: a number that overflows a double; the path of the value is current.
    if (ex.id == 406) fail(source_, path(), "must be finite, got " + last_token);
    fail(source_, "", syntax_message(position, ex.what()));
  }

 private:
  struct Frame {
    json* container;
    bool is_array;
    std::string key;        // object: key of the value being read
    std::size_t index = 0;  // array: index of the value being read
    bool streamed = false;  // array: its elements go to streamed_->element, not the tree
  };

  // Whether an array that starts now sits at streamed_->array_path: one step per open frame.
  bool at_streamed_path() const {
    const std::vector<std::string>& steps = streamed_->array_path;
    if (steps.size() != frames_.size()) return false;
    for (std::size_t k = 0; k < steps.size(); ++k) {
      const Frame& f = frames_[k];
      if (f.is_array ? steps[k] != "[]" : (steps[k] == "[]" || steps[k] != f.key)) return false;
    }
    return true;
  }

  // The element just completed in a streamed array: hand it over and drop it from the tree.
  void hand_over(Frame& f) {
    std::vector<std::size_t> indices;
    for (const Frame& g : frames_)
      if (g.is_array) indices.push_back(g.index);
    if constexpr (std::is_same_v<Json, nlohmann::json>)  // parse_ordered streams nothing
      streamed_->element(f.container->back(), indices);
    f.container->erase(f.container->size() - 1);
  }

  // "invalid JSON at line L, column C: <nlohmann's reason>"; `position` counts the characters
  // read, the last of which is the offending one.
  std::string syntax_message(std::size_t position, const std::string& what) const {
    const std::size_t at = std::min(position > 0 ? position - 1 : 0, text_.size());
    const auto line = 1 + std::count(text_.begin(), text_.begin() + static_cast<long>(at), '\n');
    const std::size_t newline = at == 0 ? std::string_view::npos : text_.rfind('\n', at - 1);
    const std::size_t column = at - (newline == std::string_view::npos ? 0 : newline + 1) + 1;
    std::string reason = what;
    const auto col = what.find("column ");
    const auto colon = col == std::string::npos ? std::string::npos : what.find(": ", col);
    if (colon != std::string::npos)
      reason = what.substr(colon + 2);
    else if (const auto bracket = what.find("] "); bracket != std::string::npos)
      reason = what.substr(bracket + 2);
    return "invalid JSON at line " + std::to_string(line) + ", column " + std::to_string(column) +
           ": " + reason;
  }

  // Every rayint format nests fewer than 10 levels; a document nested deeper than kMaxJsonDepth
  // is refused before its frames (and the DOM's recursive destruction) cost memory and stack.
  void check_depth() const {
    if (frames_.size() >= kMaxJsonDepth)
      fail(source_, "", "nested deeper than " + std::to_string(kMaxJsonDepth) + " levels (the limit)");
  }

  std::string path() const {
    std::string p;
    for (const Frame& f : frames_) p = f.is_array ? index_path(p, f.index) : member_path(p, f.key);
    return p;
  }

  // Stores `value` where the parser is and returns its address.
  json* place(json value) {
    if (frames_.empty()) {
      root_ = std::move(value);
      return &root_;
    }
    Frame& f = frames_.back();
    if (f.is_array) {
      f.container->push_back(std::move(value));
      return &f.container->back();
    }
    *member_ = std::move(value);
    return member_;
  }

  void open(json value, bool is_array) {
    json* where = place(std::move(value));
    frames_.push_back(Frame{where, is_array, {}, 0});
  }

  // A value is complete: an enclosing array moves on to its next index (after handing the value
  // over, when the array is streamed).
  bool add(json value) {
    place(std::move(value));
    return completed();
  }

  bool close() {
    frames_.pop_back();
    return completed();
  }

  bool completed() {
    if (frames_.empty() || !frames_.back().is_array) return true;
    Frame& f = frames_.back();
    if (f.streamed) hand_over(f);
    ++f.index;
    return true;
  }

  std::string_view text_;
  const std::string& source_;
  json root_;
  std::vector<Frame> frames_;  // containers being filled; pointers stay valid (see place)
  json* member_ = nullptr;
  const StreamedArray* streamed_ = nullptr;
};

template <class Json>
Json parse_with_paths(std::string_view text, const std::string& source,
                      const StreamedArray* streamed = nullptr) {
  PathTrackingBuilder<Json> builder(text, source, streamed);
  Json::sax_parse(text.begin(), text.end(), &builder, Json::input_format_t::json, /*strict=*/true,
                  /*ignore_comments=*/false);
  return builder.take_root();
}

}  // namespace

nlohmann::json parse(std::string_view text, const std::string& source) {
  return parse_with_paths<nlohmann::json>(text, source);
}

nlohmann::json parse(std::string_view text, const std::string& source,
                     const StreamedArray& streamed) {
  return parse_with_paths<nlohmann::json>(text, source, &streamed);
}

nlohmann::ordered_json parse_ordered(std::string_view text, const std::string& source) {
  return parse_with_paths<nlohmann::ordered_json>(text, source);
}

namespace {
thread_local InputFileLog* active_log = nullptr;
}  // namespace

InputFileLog::InputFileLog() : outer_(active_log) { active_log = this; }
InputFileLog::~InputFileLog() { active_log = outer_; }

void InputFileLog::note(const std::string& path) {
  if (active_log == nullptr) return;
  auto& files = active_log->files_;
  if (std::find(files.begin(), files.end(), path) == files.end()) files.push_back(path);
}

// The input byte limit is core/limits.hpp's kInputBytes (float images are read under it too).
static_assert(kDefaultMaxInputBytes == limits::kInputBytes.default_value, "one input byte limit");

std::size_t max_input_bytes() { return static_cast<std::size_t>(limits::value(limits::kInputBytes)); }

std::string read_file_bytes(const std::string& file,
                            const std::function<void(const std::string& reason)>& fail) {
  InputFileLog::note(file);
  const std::size_t limit = max_input_bytes();
  const auto too_large = [&] {
    fail("larger than the input limit of " + std::to_string(limit) +
         " bytes; RAYINT_MAX_INPUT_BYTES raises it");
  };
  // What the path is, before reading: a directory or a device (/dev/zero, a terminal) is no
  // input file; a regular file is measured first; a FIFO (/dev/stdin on a pipe) is read as a
  // stream under the same limit.
  struct stat st {};
  if (::stat(file.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) fail("is a directory");
    if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) fail("is a device, not an input file");
    if (S_ISREG(st.st_mode) && static_cast<unsigned long long>(st.st_size) > limit) too_large();
  }
  errno = 0;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(file.c_str(), "rb"), &std::fclose);
  auto cannot_read = [&fail]() {
    const int err = errno;
    fail(err != 0 ? std::strerror(err) : "read error");
  };
  if (!f) cannot_read();
  std::string bytes;
  // A regular file's size is known: one allocation instead of a doubling string, which copied
  // and faulted in about twice the file (a big mesh file: issue 33).
  if (S_ISREG(st.st_mode)) bytes.reserve(static_cast<std::size_t>(st.st_size));
  char buf[1 << 16];
  std::size_t n = 0;
  while ((n = std::fread(buf, 1, sizeof buf, f.get())) > 0) {
    if (n > limit - std::min(limit, bytes.size())) too_large();
    bytes.append(buf, n);
  }
  if (std::ferror(f.get())) cannot_read();
  return bytes;
}

FileBytes::FileBytes(FileBytes&& o) noexcept
    : mapped_(std::exchange(o.mapped_, nullptr)), size_(std::exchange(o.size_, 0)), text_(std::move(o.text_)) {}

FileBytes& FileBytes::operator=(FileBytes&& o) noexcept {
  if (this != &o) {
    if (mapped_ != nullptr) munmap(mapped_, size_);
    mapped_ = std::exchange(o.mapped_, nullptr);
    size_ = std::exchange(o.size_, 0);
    text_ = std::move(o.text_);
  }
  return *this;
}

FileBytes::~FileBytes() {
  if (mapped_ != nullptr) munmap(mapped_, size_);
}

FileBytes read_file_bytes_mapped(const std::string& file, const std::function<void(const std::string& reason)>& fail) {
  constexpr std::size_t kMinBytes = std::size_t{1} << 20;  // below: read_file_bytes (PrefaultedAllocator's bound)
  // The size is the opened file's (fstat), so a file replaced between a stat and the open cannot
  // leave a mapping longer than the file.
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return FileBytes(read_file_bytes(file, fail));  // its message
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || static_cast<unsigned long long>(st.st_size) < kMinBytes ||
      static_cast<unsigned long long>(st.st_size) > max_input_bytes()) {
    ::close(fd);
    return FileBytes(read_file_bytes(file, fail));
  }
  const auto size = static_cast<std::size_t>(st.st_size);
  void* p = mmap(nullptr, size, PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
  ::close(fd);
  if (p == MAP_FAILED) return FileBytes(read_file_bytes(file, fail));
  FileBytes out;
  out.mapped_ = static_cast<char*>(p);
  out.size_ = size;
  InputFileLog::note(file);
  return out;
}

FileBytes read_big_file(const std::string& path) {
  return read_file_bytes_mapped(path, [&path](const std::string& reason) {
    throw InputError(one_line(path + ": cannot read file (" + reason + ")"));
  });
}

std::string read_text_file(const std::string& path) {
  return read_file_bytes(path, [&path](const std::string& reason) {
    throw InputError(one_line(path + ": cannot read file (" + reason + ")"));
  });
}

}  // namespace rayint::json_source
