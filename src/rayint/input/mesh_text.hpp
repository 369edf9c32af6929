#pragma once
// Line-oriented reading of text mesh formats (TetGen .node/.ele, gmsh .msh ASCII): one cursor over
// the bytes that hands out whitespace-separated words line by line and turns every problem into
// one InputError line "<file>: <field>, line N: <what>" (core/error.hpp).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace rayint::mesh_text {

class LineCursor {
 public:
  // `comment`: a character that starts a comment running to the end of the line ('\0': none).
  LineCursor(std::string_view bytes, std::string source, char comment);

  const std::string& source() const { return source_; }
  std::size_t line_number() const { return line_no_; }
  bool at_end() const { return pos_ >= bytes_.size(); }
  std::size_t remaining_bytes() const { return bytes_.size() - pos_; }
  std::string_view rest() const { return bytes_.substr(pos_); }
  void skip_bytes(std::size_t n);  // binary payloads; fails (field) when fewer remain

  // The words of the next line that holds any (blank and comment-only lines are skipped); empty
  // at the end of the input.
  std::vector<std::string_view> words();
  // The next line as it stands (without the end of line); fails at the end of the input.
  std::string_view raw_line(const std::string& field);
  // Like words(), but fails "<field>: unexpected end of file" at the end.
  std::vector<std::string_view> need_words(const std::string& field, std::size_t at_least,
                                           const char* what);

  [[noreturn]] void fail(const std::string& field, const std::string& what) const;
  double real(std::string_view word, const std::string& field) const;  // finite
  long long integer(std::string_view word, const std::string& field, long long lo, long long hi) const;

 private:
  std::string_view bytes_;
  std::string source_;
  char comment_;
  std::size_t pos_ = 0, line_no_ = 0;
};

// Upper bound for reserving `count` items read from a header: never more than the input could
// hold at `min_bytes` bytes per item, so a forged count cannot exhaust memory before parsing fails.
std::size_t reserve_bound(std::size_t count, std::size_t remaining_bytes, std::size_t min_bytes);

}  // namespace rayint::mesh_text
