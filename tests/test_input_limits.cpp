// Inputs that would cost without bound are refused with one line naming the file and the limit
// (issue 30, "Resource limits"; docs/limits.md): JSON nested deeper than kMaxJsonDepth, a file
// larger than the input limit (RAYINT_MAX_INPUT_BYTES), a device such as /dev/zero; a FIFO
// (/dev/stdin on a pipe) is read as a stream; a float image's size is checked from its header
// before its pixels are read.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <fstream>
#include <string>

#include "test_paths.hpp"
#include "cli_harness.hpp"
#include "cli_refusal.hpp"
#include "input_text.hpp"
#include "rayint/core/format.hpp"
#include "rayint/input/json_source.hpp"
#include "rayint/render/float_image.hpp"

using rayint::test::check_refusals;
using rayint::test::line_count;
using rayint::test::TempDir;

TEST_CASE("JSON nested deeper than the limit is refused at the limit, not before",
          "[reliability][input-limits]") {
  const std::size_t d = rayint::json_source::kMaxJsonDepth;
  const std::string ok = std::string(d, '[') + std::string(d, ']');
  CHECK_NOTHROW(rayint::json_source::parse(ok, "ok.json"));
  const std::string deep = std::string(d + 1, '[') + std::string(d + 1, ']');
  CHECK_THROWS_WITH(rayint::json_source::parse(deep, "deep.json"),
                    "deep.json: (root): nested deeper than 256 levels (the limit)");
}

TEST_CASE("The CLI refuses devices, oversized and over-nested inputs with one line",
          "[reliability][input-limits]") {
  const TempDir dir;
  dir.copy_case("paper-figure-2");
  dir.write("deep.json", std::string(100000, '[') + std::string(100000, ']'));
  // Nothing written (check_refused: the folder as it was, so no out.json).
  check_refusals(dir,
                 {{"eval /dev/zero -o out.json", "/dev/zero: cannot read file (is a device, not an input file)"},
                  {"eval deep.json -o out.json", "deep.json: (root): nested deeper than 256 levels (the limit)"}},
                 true);
  const std::size_t size = rayint::test::fs::file_size(dir.path / "paper-figure-2.json");
  const std::string env = "RAYINT_MAX_INPUT_BYTES=" + std::to_string(size - 1);
  const std::string cmd = "cd '" + dir.path.string() + "' && " + env + " '" + RAYINT_CLI_PATH
                          + "' eval paper-figure-2.json -o out.json 2>err.txt; echo $? > rc.txt";
  REQUIRE(std::system(cmd.c_str()) == 0);
  CHECK(rayint::test::slurp(dir.path / "rc.txt") == "2\n");
  CHECK(rayint::test::slurp(dir.path / "err.txt") ==
        "rayint: error: paper-figure-2.json: cannot read file (larger than the input limit of " +
            std::to_string(size - 1) + " bytes; RAYINT_MAX_INPUT_BYTES raises it)\n");
  CHECK_FALSE(rayint::test::fs::exists(dir.path / "out.json"));
}

TEST_CASE("A case on standard input through a pipe is read as a stream", "[reliability][input-limits]") {
  const TempDir dir;
  dir.copy_case("paper-figure-2");
  const std::string cmd = "cd '" + dir.path.string() + "' && cat paper-figure-2.json | '" + RAYINT_CLI_PATH
                          + "' eval /dev/stdin --methods exact --no-timing >out.txt 2>err.txt; echo $? > rc.txt";
  REQUIRE(std::system(cmd.c_str()) == 0);
  INFO(rayint::test::slurp(dir.path / "err.txt"));
  CHECK(rayint::test::slurp(dir.path / "rc.txt") == "0\n");
  CHECK(rayint::test::slurp(dir.path / "out.txt").find("\"paper-figure-2\"") != std::string::npos);
}

namespace {

// A float image file that declares `header` (a .pfm or .npy header) over `data_bytes` of zeros,
// made sparse (fs::resize_file): a multi-GB image that takes no disk.
void write_sparse_image(const rayint::test::fs::path& path, const std::string& header, unsigned long long data_bytes) {
  {
    std::ofstream out(path, std::ios::binary);
    out << header;
  }
  rayint::test::fs::resize_file(path, header.size() + data_bytes);
}

// A version-1 .npy header for data of type `descr` and `shape`, padded as NumPy pads it (to a
// 64-byte multiple).
std::string npy_header(const std::string& descr, const std::string& shape) {
  std::string dict = "{'descr': '" + descr + "', 'fortran_order': False, 'shape': " + shape + ", }";
  while ((10 + dict.size() + 1) % 64 != 0) dict += ' ';
  dict += '\n';
  const std::size_t n = dict.size();
  return std::string("\x93NUMPY\x01\x00", 8) + static_cast<char>(n & 0xff) + static_cast<char>(n >> 8) + dict;
}

}  // namespace

TEST_CASE("A float image's size is checked from its header before its pixels are read (.pfm, .npy)",
          "[reliability][input-limits]") {
  // 16384 x 16384 is the largest side a reader accepts; its pixels need 16 GB here (the file,
  // the decoded doubles, alpha and float slices): above the 8 GiB image-memory limit. Before
  // this check, read_image read the whole 3.2 GB file into memory first. (Float32 data in both:
  // a float64 .npy of that size, 6.4 GB, is refused by the 4 GiB input byte limit before this.)
  const TempDir dir;
  const unsigned long long pixels = 16384ull * 16384ull;
  write_sparse_image(dir.path / "big.pfm", "PF\n16384 16384\n-1.0\n", pixels * 12);
  write_sparse_image(dir.path / "big.npy", npy_header("<f4", "(16384, 16384, 3)"), pixels * 12);
  for (const std::string name : {"big.pfm", "big.npy"}) {
    const std::string path = (dir.path / name).string();
    INFO(path);
    const std::string what = rayint::test::input_error_of([&] { rayint::read_image(path); });
    CHECK(what.rfind(path + ": (image): 16384 x 16384 pixels: ", 0) == 0);
    CHECK(what.find("bytes of image memory is above the limit of 8589934592 (RAYINT_MAX_IMAGE_BYTES=N raises it; "
                    "docs/limits.md)") != std::string::npos);
    CHECK(what.find('\n') == std::string::npos);
  }
  // Through the CLI, under a 2 GB address-space limit: the refusal is the one line, no
  // std::bad_alloc (reading either file would need 3.2 GB), and nothing is written.
  // An ASan build cannot start under ulimit -v (it reserves terabytes of shadow address space):
  // there the same refusal is checked without the limit.
#ifdef __SANITIZE_ADDRESS__
  const std::string address_limit;
#else
  const std::string address_limit = "ulimit -v 2000000; ";
#endif
  const std::string mesh_case = "'" + RAYINT_SOURCE_DIR + "/cases/mesh-linear-field.json'";
  for (const std::string name : {"big.pfm", "big.npy"}) {
    const std::string cmd = "cd '" + dir.path.string() + "' && (" + address_limit + "'" + RAYINT_CLI_PATH + "' render " +
                            mesh_case + " -o fit.npy --loss-target " + name +
                            " --grad-out g.npy -q) >out.txt 2>err.txt; echo $? > rc.txt";
    REQUIRE(std::system(cmd.c_str()) == 0);
    const std::string err = rayint::test::slurp(dir.path / "err.txt");
    INFO(err);
    CHECK(rayint::test::slurp(dir.path / "rc.txt") == "2\n");
    CHECK(line_count(err) == 1);
    CHECK(err.rfind("rayint: error: " + name + ": (image): 16384 x 16384 pixels: ", 0) == 0);
    CHECK_FALSE(rayint::test::fs::exists(dir.path / "fit.npy"));
    CHECK_FALSE(rayint::test::fs::exists(dir.path / "g.npy"));
  }
}

TEST_CASE("A float image larger than the input byte limit is refused before it is read",
          "[reliability][input-limits]") {
  const TempDir dir;
  rayint::Image im(4, 3);
  rayint::write_image((dir.path / "small.pfm").string(), im);
  const std::string path = (dir.path / "small.pfm").string();
  CHECK_NOTHROW(rayint::read_image(path));
  ::setenv("RAYINT_MAX_INPUT_BYTES", "100", 1);
  const std::string what = rayint::test::input_error_of([&] { rayint::read_image(path); });
  ::unsetenv("RAYINT_MAX_INPUT_BYTES");
  CHECK(what == path + ": (file): " + rayint::format_number(static_cast<double>(rayint::test::fs::file_size(path))) +
                    " bytes is above the limit of 100 (RAYINT_MAX_INPUT_BYTES=N raises it; docs/limits.md)");
  // Not a regular file: a directory named like an image.
  rayint::test::fs::create_directory(dir.path / "dir.npy");
  CHECK(rayint::test::input_error_of([&] { rayint::read_image((dir.path / "dir.npy").string()); }) ==
        (dir.path / "dir.npy").string() + ": not a regular file (an image's header is read before its pixels)");
}
