// Case-file reader: one test per class of input error (each checks that the one-line message
// names the file and the field), valid round-trips in both transfer-function forms, and a load
// of the whole cases/ corpus.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "test_paths.hpp"
#include "rayint/input/case_reader.hpp"
#include "rayint/input/json_source.hpp"
#include "cli_harness.hpp"
#include "input_text.hpp"

namespace {

using rayint::Case;
using rayint::InputError;
using rayint::parse_case_text;
using rayint::read_case_file;

constexpr const char* kSource = "cases/x.json";

// A valid case in the per-channel form; the error tests substitute one piece of it.
const std::string kValid = R"({
  "name": "paper-figure-2",
  "description": "Williams & Max Fig. 2, first interval",
  "transfer_function": {
    "density": [[0.0, 5.0], [1.0, 2.0]],
    "color": {"r": [[0.0, 1.7], [1.0, 1.7]], "g": [[0.0, 1.0], [1.0, 1.0]], "b": [[0.0, 0.2], [1.0, 0.2]]}
  },
  "rays": [
    {"background": [0.0, 0.0, 0.0],
     "segments": [{"length": 1.0, "scalar": [0.1, 0.9]}, {"length": 0.25, "scalar": [0.9, 0.4]}]}
  ]
})";

// kValid with the first occurrence of `from` replaced by `to` (which must exist).
std::string with(std::string_view from, std::string_view to, std::string text = kValid) {
  return rayint::test::replace_first(std::move(text), from, to);
}

// The message is `<file>: <path>: <what>` on one line.
void check_error(const std::string& text, const std::string& path, const std::string& what) {
  rayint::test::check_one_line_error(
      rayint::test::input_error_of([&] { parse_case_text(text, kSource); }), kSource, path, what);
}

}  // namespace

TEST_CASE("valid case, per-channel colour and shared density, round-trips", "[case_reader]") {
  const Case c = parse_case_text(kValid, kSource);
  CHECK(c.name == "paper-figure-2");
  CHECK(c.description == "Williams & Max Fig. 2, first interval");
  CHECK(c.source == kSource);
  for (int ch = 0; ch < rayint::kChannels; ++ch) {
    CHECK(c.transfer.density[ch].scalar == std::vector<double>{0.0, 1.0});
    CHECK(c.transfer.density[ch].value == std::vector<double>{5.0, 2.0});
  }
  CHECK(c.transfer.color[0].value == std::vector<double>{1.7, 1.7});
  CHECK(c.transfer.color[1].value == std::vector<double>{1.0, 1.0});
  CHECK(c.transfer.color[2].value == std::vector<double>{0.2, 0.2});
  REQUIRE(c.rays.size() == 1);
  CHECK(c.rays[0].background == rayint::Rgb{0.0, 0.0, 0.0});
  REQUIRE(c.rays[0].segments.size() == 2);
  CHECK(c.rays[0].segments[0].length == 1.0);
  CHECK(c.rays[0].segments[0].scalar_far == 0.1);
  CHECK(c.rays[0].segments[0].scalar_exit == 0.9);
  CHECK(c.rays[0].segments[1].length == 0.25);
  CHECK(c.rays[0].segments[1].scalar_far == 0.9);
  CHECK(c.rays[0].segments[1].scalar_exit == 0.4);
}

TEST_CASE("valid case, per-channel density and shared colour, defaults applied", "[case_reader]") {
  const Case c = parse_case_text(R"({
    "name": "n",
    "transfer_function": {
      "density": {"r": [[0, 1]], "g": [[-1, 0], [2, 4]], "b": [[0.5, 3], [0.75, 0], [1e3, 1e6]]},
      "color": [[0, 0.25], [1, 0.5]]
    },
    "rays": [{"segments": [{"length": 0, "scalar": [-2, 2]}]},
             {"background": [1, 2, 3], "segments": [{"length": 5e-3, "scalar": [7, 7]}]}]
  })",
                                 kSource);
  CHECK(c.description.empty());
  CHECK(c.transfer.density[0].scalar == std::vector<double>{0.0});
  CHECK(c.transfer.density[1].value == std::vector<double>{0.0, 4.0});
  CHECK(c.transfer.density[2].scalar == std::vector<double>{0.5, 0.75, 1e3});
  CHECK(c.transfer.density[2].value == std::vector<double>{3.0, 0.0, 1e6});
  for (int ch = 0; ch < rayint::kChannels; ++ch)
    CHECK(c.transfer.color[ch].value == std::vector<double>{0.25, 0.5});
  REQUIRE(c.rays.size() == 2);
  CHECK(c.rays[0].background == rayint::Rgb{0.0, 0.0, 0.0});
  CHECK(c.rays[0].segments[0].length == 0.0);
  CHECK(c.rays[1].background == rayint::Rgb{1.0, 2.0, 3.0});
  CHECK(c.rays[1].segments[0].scalar_far == 7.0);
}

TEST_CASE("invalid JSON reports line and column", "[case_reader]") {
  check_error(with(R"("rays": [)", R"("rays": [,)"), "(root)",
              "invalid JSON at line 8, column 12:");
  check_error("", "(root)", "invalid JSON at line 1, column 1:");
  check_error(kValid + " trailing", "(root)", "invalid JSON at line 12, column 5:");
  check_error(with("\"name\"", "// comment\n  \"name\""), "(root)", "invalid JSON at line 2");
  check_error(
      "{\"name\": \"a\nb\"}", "(root)",  // raw newline inside a string
      "invalid JSON at line 1, column 12: syntax error while parsing value - invalid string");
}

TEST_CASE("wrong types name the field", "[case_reader]") {
  check_error("[1, 2]", "(root)", "must be an object, got array");
  check_error(with(R"("paper-figure-2")", "3"), "name", "must be a non-empty string, got number");
  check_error(with(R"("paper-figure-2")", R"("")"), "name", "must be a non-empty string");
  check_error(with(R"("Williams & Max Fig. 2, first interval")", "null"), "description",
              "must be a string, got null");
  check_error(
      with(R"([[0.0, 5.0], [1.0, 2.0]])", R"("linear")"), "transfer_function.density",
      "must be a list of [scalar, value] points or an object with keys r, g, b, got string");
  check_error(with("[0.0, 5.0]", R"(["0.0", 5.0])"), "transfer_function.density[0][0]",
              "must be a number, got string");
  check_error(with("[0.0, 5.0]", "[0.0, true]"), "transfer_function.density[0][1]",
              "must be a number, got boolean");
  check_error(with("[0.0, 5.0]", "[0.0, 5.0, 1.0]"), "transfer_function.density[0]",
              "must be a [scalar, value] pair");
  check_error(with("[0.0, 5.0]", "5.0"), "transfer_function.density[0]",
              "must be a [scalar, value] pair, got number");
  check_error(with(R"("scalar": [0.1, 0.9])", R"("scalar": 0.5)"), "rays[0].segments[0].scalar",
              "must be a [far, near] pair of numbers, got number");
  check_error(with(R"("scalar": [0.9, 0.4])", R"("scalar": [0.9, "near"])"),
              "rays[0].segments[1].scalar[1]", "must be a number, got string");
  check_error(with(R"("length": 0.25)", R"("length": "1/4")"), "rays[0].segments[1].length",
              "must be a number, got string");
  check_error(with("[0.0, 0.0, 0.0]", "[0.0, 0.0]"), "rays[0].background",
              "must be an array of 3 numbers [r, g, b], got an array of 2");
  check_error(with("[0.0, 0.0, 0.0]", "{}"), "rays[0].background",
              "must be an array of 3 numbers [r, g, b], got object");
  check_error(with(R"({"length": 1.0, "scalar": [0.1, 0.9]})", "[1.0, 0.1, 0.9]"),
              "rays[0].segments[0]", "must be an object, got array");
  check_error(R"({"name": "n", "transfer_function": 7, "rays": []})", "transfer_function",
              "must be an object, got number");
}

TEST_CASE("missing required fields", "[case_reader]") {
  check_error(with(R"("name": "paper-figure-2",)", ""), "name", "missing required field");
  check_error(with(R"("density": [[0.0, 5.0], [1.0, 2.0]],)", ""), "transfer_function.density",
              "missing required field");
  check_error(with(R"(, "b": [[0.0, 0.2], [1.0, 0.2]])", ""), "transfer_function.color.b",
              "missing required field");
  check_error(with(R"("length": 0.25, )", ""), "rays[0].segments[1].length",
              "missing required field");
  check_error(with(R"(, "scalar": [0.1, 0.9])", ""), "rays[0].segments[0].scalar",
              "missing required field");
  check_error(with(R"(,
     "segments": [{"length": 1.0, "scalar": [0.1, 0.9]}, {"length": 0.25, "scalar": [0.9, 0.4]}])",
                   ""),
              "rays[0].segments", "missing required field");
  check_error(R"({"name": "n", "transfer_function": {"density": [[0, 1]], "color": [[0, 1]]}})",
              "rays", "missing required field");
}

TEST_CASE("unknown and duplicate fields are errors", "[case_reader]") {
  check_error(with(R"("g": [[0.0, 1.0], [1.0, 1.0]])", R"("q": [[0.0, 1.0], [1.0, 1.0]])"),
              "transfer_function.color.q", "unknown field (expected r, g, b)");
  check_error(with(R"("description")", R"("descripton")"), "descripton",
              "unknown field (expected name, description, transfer_function, rays)");
  check_error(with(R"("segments")", R"("segmnts")"), "rays[0].segmnts",
              "unknown field (expected background, segments)");
  check_error(with(R"("length": 0.25)", R"("length": 0.25, "weight": 1)"),
              "rays[0].segments[1].weight", "unknown field (expected length, scalar)");
  check_error(with(R"("density")", R"("opacity": [], "density")"), "transfer_function.opacity",
              "unknown field (expected density, color)");
  check_error(with(R"("length": 0.25)", R"("length": 0.25, "length": 0.5)"),
              "rays[0].segments[1].length", "duplicate field");
}

TEST_CASE("non-finite numbers (1e999 overflows a double) are rejected", "[case_reader]") {
  check_error(with("[1.0, 2.0]", "[1.0, 1e999]"), "transfer_function.density[1][1]",
              "must be finite, got 1e999");
  check_error(with("[1.0, 2.0]", "[-1e999, 2.0]"), "transfer_function.density[1][0]",
              "must be finite, got -1e999");
  check_error(with(R"("length": 1.0)", R"("length": 1e400)"), "rays[0].segments[0].length",
              "must be finite");
  check_error(with("[0.9, 0.4]", "[0.9, -2e308]"), "rays[0].segments[1].scalar[1]",
              "must be finite");
  check_error(with("[0.0, 0.0, 0.0]", "[0.0, 1e999, 0.0]"), "rays[0].background[1]",
              "must be finite");
  check_error(with("[0.0, 1.7]", "[0.0, 1E+999]"), "transfer_function.color.r[0][1]",
              "must be finite");
}

TEST_CASE("negative values are rejected", "[case_reader]") {
  check_error(with("[1.0, 2.0]", "[1.0, -2.0]"), "transfer_function.density[1][1]",
              "must be finite and >= 0, got -2");
  check_error(with("[1.0, 0.2]", "[1.0, -0.5]"), "transfer_function.color.b[1][1]",
              "must be finite and >= 0, got -0.5");
  check_error(with("[0.0, 0.0, 0.0]", "[0.0, 0.0, -1e-300]"), "rays[0].background[2]",
              "must be finite and >= 0, got -1e-300");
  // -0 is >= 0; it is read as +0.
  const Case c = parse_case_text(with("[0.0, 0.0, 0.0]", "[-0.0, 0, 0]"), kSource);
  CHECK(c.rays[0].background[0] == 0.0);
  CHECK(!std::signbit(c.rays[0].background[0]));
  // Negative scalars are fine: the scalar axis is unconstrained.
  CHECK_NOTHROW(parse_case_text(with("[0.1, 0.9]", "[-0.1, -0.9]"), kSource));
}

TEST_CASE("negative segment lengths are rejected", "[case_reader]") {
  check_error(with(R"("length": 0.25)", R"("length": -1)"), "rays[0].segments[1].length",
              "must be finite and >= 0, got -1");
  check_error(with(R"("length": 1.0)", R"("length": -1e-20)"), "rays[0].segments[0].length",
              "must be finite and >= 0, got -1e-20");
  CHECK_NOTHROW(parse_case_text(with(R"("length": 1.0)", R"("length": 0)"), kSource));
}

TEST_CASE("breakpoints must be non-decreasing, a scalar at most twice (a jump)", "[case_reader]") {
  // Twice: a jump (left value, right value); three times: refused.
  CHECK_NOTHROW(parse_case_text(with("[[0.0, 5.0], [1.0, 2.0]]", "[[0.0, 5.0], [0.5, 1.0], [0.5, 2.0]]"), kSource));
  check_error(with("[[0.0, 5.0], [1.0, 2.0]]", "[[0.0, 5.0], [0.5, 1.0], [0.5, 2.0], [0.5, 3.0]]"),
              "transfer_function.density[3][0]",
              "scalar 0.5 appears three times (at most twice: a jump's left and right values)");
  check_error(with("[[0.0, 0.2], [1.0, 0.2]]", "[[0.0, 0.2], [-1.0, 0.2]]"),
              "transfer_function.color.b[1][0]",
              "scalar points must be non-decreasing (-1 after 0)");
  // Points one ulp apart are allowed.
  CHECK_NOTHROW(parse_case_text(
      with("[[0.0, 5.0], [1.0, 2.0]]", "[[0.7, 5.0], [0.7000000000000001, 2.0]]"), kSource));
}

TEST_CASE("empty transfer functions, rays and segments are rejected", "[case_reader]") {
  check_error(with("[[0.0, 5.0], [1.0, 2.0]]", "[]"), "transfer_function.density",
              "must be a non-empty array of [scalar, value] points, got []");
  const std::string no_rays =
      R"({"name": "n", "transfer_function": {"density": [[0, 1]], "color": [[0, 1]]}, "rays": []})";
  check_error(no_rays, "rays", "must be a non-empty array, got []");
  check_error(with("\"rays\": [", "\"rays\": {\"0\": ", with("]\n}", "}\n}")), "rays",
              "must be a non-empty array, got object");
}

TEST_CASE("empty segment lists are rejected", "[case_reader]") {
  const std::string text =
      R"({"name": "n", "transfer_function": {"density": [[0, 1]], "color": [[0, 1]]},
          "rays": [{"segments": [{"length": 1, "scalar": [0, 1]}]}, {"segments": []}]})";
  check_error(text, "rays[1].segments", "must be a non-empty array, got []");
}

TEST_CASE("unreadable files name the file and the reason", "[case_reader]") {
  const std::string missing = "cases/no-such-case-file.json";
  try {
    read_case_file(missing);
    FAIL("no exception");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()) == missing + ": cannot read file (No such file or directory)");
  }
  const std::string dir = RAYINT_SOURCE_DIR + "/cases";
  try {
    read_case_file(dir);
    FAIL("no exception");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).rfind(dir + ": cannot read file (", 0) == 0);
  }
}

TEST_CASE("file errors carry the file name", "[case_reader]") {
  namespace fs = std::filesystem;
  const fs::path tmp = fs::temp_directory_path() / "rayint_case_reader_bad.json";
  {
    std::FILE* f = std::fopen(tmp.string().c_str(), "wb");
    REQUIRE(f != nullptr);
    const std::string text = with(R"("length": 0.25)", R"("length": -1)");
    std::fwrite(text.data(), 1, text.size(), f);
    std::fclose(f);
  }
  try {
    read_case_file(tmp.string());
    FAIL("no exception");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()) ==
          tmp.string() + ": rays[0].segments[1].length: must be finite and >= 0, got -1");
  }
  fs::remove(tmp);
}

TEST_CASE("every case in cases/ loads", "[case_reader][corpus]") {
  namespace fs = std::filesystem;
  const std::vector<std::string> files = rayint::list_case_files(RAYINT_SOURCE_DIR + "/cases");
  for (const auto& file : files) {
    INFO("file: " << file);
    CHECK(fs::path(file).filename() != rayint::kGateConfigName);
    Case c;
    REQUIRE_NOTHROW(c = read_case_file(file));
    CHECK(c.name == fs::path(file).stem().string());  // file name = case name + .json
    CHECK(!c.description.empty());
  }
  CHECK(files.size() >= 20);
}

TEST_CASE("paper-figure-2 reproduces the paper's interval coefficients", "[case_reader][corpus]") {
  // Williams & Max Sec. 3.3, first interval of Fig. 2: rho_r = a + b s, kappa_r rho_r = f + g s
  // with a = 5, b = -3, f = 8.5, g = -5.1, h = 0.
  const Case c = read_case_file(RAYINT_SOURCE_DIR + "/cases/paper-figure-2.json");
  const auto& rho = c.transfer.density[0];
  const auto& kappa = c.transfer.color[0];
  CHECK(rho(0.0) == 5.0);
  CHECK(rho(1.0) - rho(0.0) == -3.0);
  CHECK(kappa(0.0) * rho(0.0) == Approx(8.5).epsilon(1e-15));
  CHECK(kappa(1.0) * rho(1.0) - kappa(0.0) * rho(0.0) == Approx(-5.1).epsilon(1e-15));
  CHECK(kappa(0.25) == 1.7);
}

// ---------------------------------------------------------------------------------------------
// Streaming segments (parse_case_text) against the whole-tree walk (detail::parse_case_text_tree):
// the same Case, bit for bit, and the same first message.

namespace {

void check_same_case(const Case& a, const Case& b) {
  CHECK(a.name == b.name);
  CHECK(a.description == b.description);
  CHECK(a.source == b.source);
  for (int ch = 0; ch < rayint::kChannels; ++ch) {
    CHECK(a.transfer.density[ch].scalar == b.transfer.density[ch].scalar);
    CHECK(a.transfer.density[ch].value == b.transfer.density[ch].value);
    CHECK(a.transfer.color[ch].scalar == b.transfer.color[ch].scalar);
    CHECK(a.transfer.color[ch].value == b.transfer.color[ch].value);
  }
  REQUIRE(a.rays.size() == b.rays.size());
  for (std::size_t i = 0; i < a.rays.size(); ++i) {
    INFO("ray " << i);
    CHECK(a.rays[i].background == b.rays[i].background);
    REQUIRE(a.rays[i].segments.size() == b.rays[i].segments.size());
    std::size_t differ = 0;  // compared as bits: -0 and +0, and every last ulp
    for (std::size_t k = 0; k < a.rays[i].segments.size(); ++k) {
      const rayint::Segment& x = a.rays[i].segments[k];
      const rayint::Segment& y = b.rays[i].segments[k];
      if (std::memcmp(&x, &y, sizeof x) != 0) ++differ;
    }
    CHECK(differ == 0);
  }
}

std::string message_of(const std::string& text, bool streamed) {
  return rayint::test::input_error_of([&] {
    if (streamed)
      parse_case_text(text, kSource);
    else
      rayint::detail::parse_case_text_tree(text, kSource);
  });
}

}  // namespace

TEST_CASE("streamed segments give the whole-tree reader's case on every file in cases/",
          "[case_reader][corpus]") {
  const std::vector<std::string> files = rayint::list_case_files(RAYINT_SOURCE_DIR + "/cases");
  REQUIRE(files.size() >= 20);
  std::size_t segments = 0;
  for (const auto& file : files) {
    INFO("file: " << file);
    const std::string text = rayint::json_source::read_text_file(file);
    const Case streamed = parse_case_text(text, file);
    const Case tree = rayint::detail::parse_case_text_tree(text, file);
    check_same_case(streamed, tree);
    for (const auto& r : streamed.rays) segments += r.segments.size();
  }
  CHECK(segments > 500);  // the corpus holds many-segment cases (908 segments), not only one-liners
}

TEST_CASE("streamed segments: the same first message as the whole-tree reader", "[case_reader]") {
  // One problem each, then two problems where the streamed segment is met first in the text but
  // the walk reports the other one first (syntax errors, the root's fields, a ray's own fields,
  // the transfer function written after the rays), then problems in several rays.
  const std::string bad_segment = with(R"("length": 0.25)", R"("length": -1)");
  const std::string tf_after_rays = R"({"name": "n",
    "rays": [{"segments": [{"length": -1, "scalar": [0, 1]}]}],
    "transfer_function": {"density": [[0, -1]], "color": [[0, 1]]}})";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {bad_segment, "rays[0].segments[1].length: must be finite and >= 0, got -1"},
      {with(R"("scalar": [0.1, 0.9])", R"("scalar": 0.5)"), "rays[0].segments[0].scalar"},
      {with(R"({"length": 1.0, "scalar": [0.1, 0.9]})", "7"), "rays[0].segments[0]: must be an object"},
      {with(R"("length": 0.25)", R"("length": 0.25, "length": 0.5)"), "duplicate field"},
      {with(R"("length": 1.0)", R"("length": 1e400)"), "rays[0].segments[0].length: must be finite"},
      {bad_segment + " trailing", "(root): invalid JSON at line 12"},
      {with(R"("description")", R"("descripton")", bad_segment), "descripton: unknown field"},
      {with(R"("segments")", R"("weight": 1, "segments")", bad_segment), "rays[0].weight: unknown field"},
      {with("[0.0, 0.0, 0.0]", "[0.0, -1, 0.0]", bad_segment), "rays[0].background[1]"},
      {tf_after_rays, "transfer_function.density[0][1]"},
      {R"({"name": "n", "transfer_function": {"density": [[0, 1]], "color": [[0, 1]]},
          "rays": [{"segments": [{"length": 1, "scalar": [0, 1]}]},
                   {"segments": [{"length": 1, "scalar": [0, 1]}, {"length": -2, "scalar": [0, 1]},
                                 {"length": -3, "scalar": [0, 1]}]},
                   {"segments": [{"length": -4, "scalar": [0, 1]}]}]})",
       "rays[1].segments[1].length: must be finite and >= 0, got -2"},
      {R"({"name": "n", "transfer_function": {"density": [[0, 1]], "color": [[0, 1]]},
          "rays": [{"segments": []}, {"segments": [{"length": -1, "scalar": [0, 1]}]}]})",
       "rays[0].segments: must be a non-empty array, got []"},
      {R"({"name": "n", "transfer_function": {"density": [[0, 1]], "color": [[0, 1]]},
          "rays": [{"segments": {"0": {"length": 1, "scalar": [0, 1]}}}]})",
       "rays[0].segments: must be a non-empty array, got object"},
  };
  for (const auto& [text, expected] : cases) {
    INFO("text: " << text);
    const std::string tree = message_of(text, false);
    CHECK(message_of(text, true) == tree);
    CHECK(tree.find(expected) != std::string::npos);
  }
}

TEST_CASE("read_big_file gives read_text_file's bytes and messages", "[case_reader][reader]") {
  // A file of 1 MiB or more is mapped (json_source.hpp, FileBytes); smaller ones, directories and
  // missing files go through read_text_file's path. Bytes and messages must not depend on which.
  namespace fs = std::filesystem;
  const rayint::test::TempDir tmp;  // removed with its files at the end
  const fs::path dir = tmp.path;
  for (const std::size_t size : {std::size_t{0}, std::size_t{1000}, (std::size_t{1} << 20) - 1, std::size_t{1} << 20,
                                 (std::size_t{3} << 20) + 17}) {
    INFO("size " << size);
    std::string bytes(size, '\0');
    for (std::size_t i = 0; i < size; ++i) bytes[i] = static_cast<char>((i * 2654435761u) >> 13);
    const fs::path file = dir / ("f" + std::to_string(size));
    {
      std::FILE* f = std::fopen(file.string().c_str(), "wb");
      REQUIRE(f != nullptr);
      std::fwrite(bytes.data(), 1, bytes.size(), f);
      std::fclose(f);
    }
    rayint::json_source::FileBytes big = rayint::json_source::read_big_file(file.string());
    CHECK(big.view().size() == size);
    CHECK(big.view() == std::string_view(bytes));
    CHECK(rayint::json_source::read_text_file(file.string()) == bytes);
    const rayint::json_source::FileBytes moved = std::move(big);
    CHECK(moved.view() == std::string_view(bytes));
    fs::remove(file);
  }
  const auto message = [](auto read, const std::string& path) {
    try {
      read(path);
    } catch (const rayint::InputError& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  for (const std::string& path : std::vector<std::string>{dir.string(), (dir / "missing.vtk").string()}) {
    const std::string big = message([](const std::string& p) { (void)rayint::json_source::read_big_file(p); }, path);
    CHECK(big == message([](const std::string& p) { (void)rayint::json_source::read_text_file(p); }, path));
    CHECK(big.find("cannot read file") != std::string::npos);
  }
}
