// Line-oriented reading of text mesh formats (see mesh_text.hpp).
#include "rayint/input/mesh_text.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "rayint/core/error.hpp"

namespace rayint::mesh_text {

LineCursor::LineCursor(std::string_view bytes, std::string source, char comment)
    : bytes_(bytes), source_(std::move(source)), comment_(comment) {}

void LineCursor::fail(const std::string& field, const std::string& what) const {
  field::fail(source_, field + (line_no_ > 0 ? ", line " + std::to_string(line_no_) : ""), what);
}

std::string_view LineCursor::raw_line(const std::string& field) {
  if (at_end()) fail(field, "unexpected end of file");
  std::size_t end = bytes_.find('\n', pos_);
  if (end == std::string_view::npos) end = bytes_.size();
  std::string_view line = bytes_.substr(pos_, end - pos_);
  pos_ = end < bytes_.size() ? end + 1 : end;
  ++line_no_;
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  return line;
}

std::vector<std::string_view> LineCursor::words() {
  std::vector<std::string_view> out;
  while (out.empty() && !at_end()) {
    std::string_view line = raw_line("");
    if (comment_ != '\0') {
      const std::size_t c = line.find(comment_);
      if (c != std::string_view::npos) line = line.substr(0, c);
    }
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r' || line[i] == '\v' || line[i] == '\f')) ++i;
      std::size_t j = i;
      while (j < line.size() && !(line[j] == ' ' || line[j] == '\t' || line[j] == '\r' || line[j] == '\v' || line[j] == '\f')) ++j;
      if (j > i) out.push_back(line.substr(i, j - i));
      i = j;
    }
  }
  return out;
}

std::vector<std::string_view> LineCursor::need_words(const std::string& field, std::size_t at_least,
                                                     const char* what) {
  std::vector<std::string_view> w = words();
  if (w.empty()) fail(field, std::string("unexpected end of file (expected ") + what + ")");
  if (w.size() < at_least)
    fail(field, "expected " + std::string(what) + " (" + std::to_string(at_least) + " numbers), got " +
                    std::to_string(w.size()));
  return w;
}

void LineCursor::skip_bytes(std::size_t n) {
  if (n > remaining_bytes()) fail("binary data", "truncated: need " + std::to_string(n) + " bytes, " +
                                                     std::to_string(remaining_bytes()) + " left");
  // Counted into a local (std::count): adding to the member line_no_ byte by byte kept the loop
  // from vectorising (a char store may alias it); ~3% of a binary .msh load (issue 33).
  const char* p = bytes_.data() + pos_;
  line_no_ += static_cast<std::size_t>(std::count(p, p + n, '\n'));
  pos_ += n;
}

double LineCursor::real(std::string_view word, const std::string& field) const {
  double v = 0.0;
  const char* b = word.data();
  const char* e = word.data() + word.size();
  if (b != e && *b == '+') ++b;  // from_chars takes no leading '+'
  const auto r = std::from_chars(b, e, v);
  if (r.ec != std::errc() || r.ptr != e || !std::isfinite(v))
    fail(field, "expected a finite number, got " + field::quoted(std::string(word)));
  return v;
}

long long LineCursor::integer(std::string_view word, const std::string& field, long long lo,
                              long long hi) const {
  long long v = 0;
  const char* b = word.data();
  const char* e = word.data() + word.size();
  if (b != e && *b == '+') ++b;
  const auto r = std::from_chars(b, e, v);
  if (r.ec != std::errc() || r.ptr != e)
    fail(field, "expected an integer, got " + field::quoted(std::string(word)));
  if (v < lo || v > hi)
    fail(field, std::to_string(v) + " is out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return v;
}

std::size_t reserve_bound(std::size_t count, std::size_t remaining_bytes, std::size_t min_bytes) {
  return std::min(count, remaining_bytes / (min_bytes == 0 ? 1 : min_bytes) + 1);
}

}  // namespace rayint::mesh_text
