#pragma once
// What every fuzz target checks of a refusal, and how it reports a finding: each check traps
// (__builtin_trap), so libFuzzer saves the input as a crash artifact. A refusal must be one
// InputError line starting "<source>: " (the file it names, as the CLI prints it).
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "rayint/core/error.hpp"
#include "rayint/model/ray.hpp"

namespace rayint::fuzz {

inline void require(bool ok) {
  if (!ok) __builtin_trap();
}

// `what` is one line (no CR or LF) starting with one of `prefixes` (a reader that reads several
// files names the one it refuses).
inline void check_line_starts(const std::string& what, const std::vector<std::string>& prefixes) {
  bool named = false;
  for (const std::string& prefix : prefixes) named = named || what.compare(0, prefix.size(), prefix) == 0;
  require(named);
  require(what.find('\n') == std::string::npos && what.find('\r') == std::string::npos);
}

// `what` is one line (no CR or LF) starting "<source>: ".
inline void check_message(const std::string& what, const std::string& source) {
  check_line_starts(what, {source + ": "});
}

// Runs `body` (a reader on the input, then the checks of what it accepted); an InputError it
// throws must be one line starting with one of `prefixes`. Returns 0, libFuzzer's "go on".
template <class Body>
int refusals_start_with(const std::vector<std::string>& prefixes, Body&& body) {
  try {
    body();
  } catch (const InputError& e) {
    check_line_starts(e.what(), prefixes);
  }
  return 0;
}

// The same with the one prefix "<source>: ".
template <class Body>
int refusals_are_one_line(const std::string& source, Body&& body) {
  return refusals_start_with({source + ": "}, body);
}

// The same for what a merge does with parts a reader accepted: its consistency checks across
// parts throw std::invalid_argument, an expected refusal of parts that do not fit together.
template <class Body>
int merge_refusals_are_one_line(const std::string& source, Body&& body) {
  try {
    return refusals_are_one_line(source, body);
  } catch (const std::invalid_argument&) {
  }
  return 0;
}

// The fixed case the candidate parsers' matches run against: named "fig2" (file fig2.json), one
// ray per entry of `segments` with that many (zero) segments, every transfer function two nodes.
inline Case fig2_case(const std::vector<std::size_t>& segments) {
  Case c;
  c.name = "fig2";
  c.source = "fig2.json";
  for (int ch = 0; ch < kChannels; ++ch) {
    c.transfer.density[ch] = {{0.0, 1.0}, {5.0, 2.0}};
    c.transfer.color[ch] = {{0.0, 1.0}, {1.0, 1.0}};
  }
  for (const std::size_t m : segments) c.rays.emplace_back().segments.resize(m);
  return c;
}

// A candidate parser's target (candidate_parser, grad_candidate_parser): the input, as the text of
// the file `source`, through `parse` (parse_candidate_text or parse_grad_candidate_text); what it
// accepts names a case and `source`, and passes `check` (the format's guarantees, then the match
// against a fig2_case). Refusals are one line starting "<source>: ". Returns 0.
template <class Parsed>
int check_candidate_parser(Parsed (*parse)(std::string_view, const std::string&), void (*check)(const Parsed&),
                           const std::uint8_t* data, std::size_t size, const std::string& source) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  return refusals_are_one_line(source, [&] {
    const Parsed c = parse(text, source);
    require(!c.case_name.empty() && c.source == source);
    check(c);
  });
}

}  // namespace rayint::fuzz
