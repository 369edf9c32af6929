// Float images (render/float_image.hpp), the image check (render/image_compare.hpp, `rayint
// check --candidate-image`) and JUnit output (report/junit.hpp, `--junit` on check and gate).
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "test_paths.hpp"
#include "candidate_images.hpp"
#include "cli_harness.hpp"
#include "cli_refusal.hpp"
#include "rayint/core/error.hpp"
#include "rayint/render/float_image.hpp"
#include "rayint/render/image_compare.hpp"
#include "rayint/geometry/bounds.hpp"
#include "rayint/geometry/camera.hpp"
#include "rayint/scattering/volume_path_tracer.hpp"

namespace {

using namespace rayint;
using namespace rayint::test;

const fs::path kFixtures = fs::path(RAYINT_SOURCE_DIR) / "tests" / "fixtures" / "images";

// The value scripts/make-image-fixtures.sh put at pixel (x, y), channel c (y = 0 the top row).
double fixture_value(int x, int y, int c) { return (20.0 * x + 60.0 * y + 3.0 * c + 1.0) / 255.0; }

void check_fixture(const Image& im, bool grey, double rel_tol) {
  REQUIRE(im.width == 4);
  REQUIRE(im.height == 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x)
      for (int c = 0; c < 3; ++c) {
        INFO("pixel (" << x << ", " << y << ") channel " << c);
        const double want = fixture_value(x, y, grey ? 0 : c);
        CHECK(std::fabs(im.at(x, y)[c] - want) <= rel_tol * want);
      }
}

Image test_image(int w, int h) {
  Image im(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) im.at(x, y) = {0.1 * x + 1e-3 * y, 1.0 / (1 + x + y), y * 0.25 - 0.5};
  return im;
}

// A mesh case with a 16 x 12 camera (not square, so a transposed reader would be caught).
const std::string kCameraCase = R"({
  "name": "cube-camera",
  "transfer_function": {"density": [[0.0, 1.0], [0.5, 4.0], [1.0, 0.5]],
    "color": {"r": [[0.0, 0.9]], "g": [[0.0, 0.2], [1.0, 1.0]], "b": [[0.3, 0.1], [0.8, 0.7]]}},
  "mesh": {"points": [[0,0,0],[1,0,0],[0,1,0],[1,1,0],[0,0,1],[1,0,1],[0,1,1],[1,1,1]],
           "scalars": [0.2, 0.8, 0.5, 1.1, 0.1, 0.7, 0.4, 1.0],
           "tets": [[0,1,3,7],[0,1,7,5],[0,2,7,3],[0,2,6,7],[0,4,5,7],[0,4,7,6]]},
  "background": [0.05, 0.1, 0.2],
  "camera": {"position": [2.2, 1.6, 3.0], "look_at": [0.5, 0.5, 0.5], "fov_deg": 35, "width": 16, "height": 12}
})";

// Failing testcase names of a JUnit file, parsed by Python's xml.etree (an independent parser):
// "OK <tests> <failures>" then one name per line, or the parser's error.
std::string junit_failures(const fs::path& file) {
  TempDir tmp;
  const std::string script =
      "import sys, xml.etree.ElementTree as ET\n"
      "root = ET.parse(sys.argv[1]).getroot()\n"
      "assert root.tag == 'testsuites', root.tag\n"
      "cases = [c for s in root.findall('testsuite') for c in s.findall('testcase')]\n"
      "failed = [c for c in cases if c.find('failure') is not None]\n"
      "print('OK', len(cases), len(failed))\n"
      "for c in failed: print(c.get('name'), '|', c.find('failure').get('message'))\n";
  tmp.write("p.py", script);
  const fs::path out = tmp.path / "out.txt";
  const std::string cmd = "/usr/bin/python3 '" + (tmp.path / "p.py").string() + "' '" + file.string() +
                          "' > '" + out.string() + "' 2>&1";
  const int rc = std::system(cmd.c_str());
  return (rc == 0 ? "" : "python failed: ") + slurp(out);
}

}  // namespace

TEST_CASE("float images: files written by numpy, netpbm and OpenImageIO read with y = 0 the top row", "[image]") {
  check_fixture(read_image((kFixtures / "grad_f8.npy").string()), false, 1e-15);
  check_fixture(read_image((kFixtures / "grad_f4.npy").string()), false, 1e-7);
  check_fixture(read_image((kFixtures / "grad_grey.npy").string()), true, 1e-15);
  check_fixture(read_image((kFixtures / "grad_netpbm_be.pfm").string()), false, 1e-7);  // big-endian
  check_fixture(read_image((kFixtures / "grad_netpbm_le.pfm").string()), false, 1e-7);  // little-endian
  check_fixture(read_image((kFixtures / "grad_oiio.exr").string()), false, 1e-7);
  check_fixture(read_image((kFixtures / "grad_oiio_half.exr").string()), false, 1e-3);  // half: 11 bits
  // The 8-bit source, through the PNG-independent PPM: not read by rayint, so only the float files.
}

TEST_CASE("float images: an RGBA EXR written by OpenImageIO keeps its alpha channel", "[image][alpha]") {
  // oiiotool's "fill:left=0.25:right=1" alpha: 0.25, 0.5, 0.75, 1 by column, every row
  // (scripts/make-image-fixtures.sh); oiiotool --printstats reports mean 0.625, sd 0.2795.
  const ImageWithAlpha img = read_image_with_alpha((kFixtures / "grad_rgba_oiio.exr").string());
  check_fixture(img.rgb, false, 1e-7);
  REQUIRE(img.alpha.size() == 12);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) {
      INFO("pixel (" << x << ", " << y << ")");
      CHECK(img.alpha[static_cast<std::size_t>(y * 4 + x)] == 0.25 * (x + 1));
    }
  // read_image drops the alpha and gives the same RGB
  check_fixture(read_image((kFixtures / "grad_rgba_oiio.exr").string()), false, 1e-7);
}

TEST_CASE("float images: write and read back (npy bit for bit, pfm and exr to float32)", "[image]") {
  const Image im = test_image(7, 5);
  const Image npy = decode_npy(encode_npy(im), "x.npy");
  const Image pfm = decode_pfm(encode_pfm(im), "x.pfm");
  const Image exr = decode_exr(encode_exr(im), "x.exr");
  for (const Image* back : {&npy, &pfm, &exr}) {
    REQUIRE(back->width == 7);
    REQUIRE(back->height == 5);
  }
  for (std::size_t i = 0; i < im.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      CHECK(npy.pixels[i][c] == im.pixels[i][c]);
      CHECK(pfm.pixels[i][c] == static_cast<double>(static_cast<float>(im.pixels[i][c])));
      CHECK(exr.pixels[i][c] == static_cast<double>(static_cast<float>(im.pixels[i][c])));
    }
  // PFM's rows run bottom to top: the first float after the header is pixel (0, height-1) red.
  const std::string bytes = encode_pfm(im);
  const std::size_t header = std::string("PF\n7 5\n-1.0\n").size();
  REQUIRE(bytes.compare(0, header, "PF\n7 5\n-1.0\n") == 0);
  float first = 0.0f;
  std::memcpy(&first, bytes.data() + header, 4);
  CHECK(first == static_cast<float>(im.at(0, 4)[0]));
}

TEST_CASE("float images: malformed files give one InputError line naming the file", "[image]") {
  const Image im = test_image(3, 2);
  auto expect_error = [](auto decode, const std::string& bytes, const std::string& fragment) {
    try {
      decode(bytes, "bad.img");
      FAIL("accepted: " << fragment);
    } catch (const InputError& e) {
      const std::string what = e.what();
      INFO(what);
      CHECK(what.rfind("bad.img: ", 0) == 0);
      CHECK(what.find('\n') == std::string::npos);
      CHECK(what.find(fragment) != std::string::npos);
    }
  };
  const std::string pfm = encode_pfm(im), npy = encode_npy(im), exr = encode_exr(im);
  expect_error(decode_pfm, pfm.substr(0, pfm.size() - 1), "bytes of data");
  expect_error(decode_pfm, "PF\n3 x\n-1\n", "header");
  expect_error(decode_pfm, "PF\n0 2\n-1\n", "image size");
  expect_error(decode_pfm, "PF\n99999 2\n-1\n", "image size");
  expect_error(decode_pfm, "P6\n3 2\n255\n", "not a PFM");
  expect_error(decode_npy, npy.substr(0, npy.size() - 8), "bytes of data");
  std::string int_npy = npy;
  int_npy.replace(int_npy.find("<f8"), 3, "<i4");
  expect_error(decode_npy, int_npy, "dtype");
  std::string fortran = npy;
  fortran.replace(fortran.find("False"), 5, "True ");
  expect_error(decode_npy, fortran, "fortran_order");
  expect_error(decode_npy, "not numpy", "bad magic");
  expect_error(decode_exr, exr.substr(0, exr.size() / 2), "exr: ");
  expect_error(decode_exr, "v/1", "not an OpenEXR");
  expect_error(decode_exr, std::string("v/1\x01", 4) + std::string(40, '\xff'), "exr: ");
  CHECK_THROWS_AS(image_format_of("x.tiff"), InputError);
}

TEST_CASE("image comparison: figures on a known difference", "[image]") {
  const Image exact = test_image(5, 4);
  Image cand = exact;
  cand.at(3, 2)[1] += 1e-3;  // one channel of one pixel
  ImageCompareOptions o;
  o.rel_tol = 1e-6;
  o.worst = 2;
  const ImageComparison c = compare_images(exact, cand, o);
  CHECK_FALSE(c.pass);
  CHECK(c.failed_pixels == 1);
  CHECK(c.failed_channels == 1);
  CHECK(c.fraction_within == Approx(19.0 / 20.0));
  CHECK(c.max_abs == Approx(1e-3).epsilon(1e-9));
  CHECK(c.mean_abs == Approx(1e-3 / 60.0).epsilon(1e-9));
  const double peak = 1.0;  // test_image's largest |value|: 1/(1+0+0)
  CHECK(c.psnr == Approx(10.0 * std::log10(peak * peak / (1e-6 / 60.0))).epsilon(1e-9));
  REQUIRE(c.worst.size() == 2);
  CHECK(c.worst[0].x == 3);
  CHECK(c.worst[0].y == 2);
  CHECK(c.worst[0].channel == 1);
  CHECK_FALSE(c.worst[0].pass);
  CHECK(c.worst[1].pass);
  // Flips: a top-bottom mirror of the candidate is undone by flip_y.
  const ImageComparison same = compare_images(exact, flipped(flipped(exact, true, true), true, true), o);
  CHECK(same.pass);
  CHECK(std::isinf(same.psnr));
  CHECK_FALSE(compare_images(exact, flipped(exact, false, true), o).pass);
  CHECK_THROWS_AS(compare_images(exact, test_image(4, 5), o), std::invalid_argument);
}

TEST_CASE("CLI: render writes pfm, exr and npy, and the exact image passes its own check", "[image]") {
  TempDir dir;
  dir.write("cam.json", kCameraCase);
  for (const std::string ext : {"npy", "pfm", "exr"}) {
    INFO(ext);
    const auto r = run_cli(dir.path, "render cam.json -o exact." + ext + " --quiet --threads 2");
    INFO(r.err);
    REQUIRE(r.status == 0);
    const auto c = run_cli(dir.path, "check cam.json --candidate-image exact." + ext + " -o diff.json --junit j.xml --threads 2");
    INFO(c.err);
    CHECK(c.status == 0);
    const auto diff = nlohmann::json::parse(slurp(dir.path / "diff.json"));
    CHECK(diff["pass"] == true);
    CHECK(diff["fraction_within_tolerance"] == 1.0);
    CHECK(diff["pixel_convention"].get<std::string>().find("top") != std::string::npos);
    if (ext == "npy") CHECK(diff["abs_error"]["max"] == 0.0);  // float64: bit for bit
    else CHECK(diff["rel_error"]["max"].get<double>() <= 6.0e-8);  // float32 rounding: 2^-24
    CHECK(junit_failures(dir.path / "j.xml").rfind("OK 4 0", 0) == 0);  // summary + 3 worst pixels
  }
  // The same picture in PNG passes only at 8-bit precision.
  const Image npy = read_image((dir.path / "exact.npy").string());
  CHECK(npy.width == 16);
  CHECK(npy.height == 12);
}

TEST_CASE("CLI: one pixel off by 1e-3 fails, JUnit names it, the worst pixel replays with eval", "[image]") {
  TempDir dir;
  dir.write("cam.json", kCameraCase);
  REQUIRE(run_cli(dir.path, "render cam.json -o exact.npy --quiet").status == 0);
  Image im = read_image((dir.path / "exact.npy").string());
  const double expected = im.at(9, 4)[1];
  im.at(9, 4)[1] += 1e-3;
  write_image((dir.path / "off.npy").string(), im);
  fs::create_directories(dir.path / "art");
  const auto r = run_cli(dir.path, "check cam.json --candidate-image off.npy --artifacts art -o diff.json --junit j.xml");
  INFO(r.err);
  CHECK(r.status == 1);
  const auto diff = nlohmann::json::parse(slurp(dir.path / "diff.json"));
  CHECK(diff["pass"] == false);
  CHECK(diff["failed_pixels"] == 1);
  CHECK(diff["worst_pixels"][0]["x"] == 9);
  CHECK(diff["worst_pixels"][0]["y"] == 4);
  CHECK(diff["worst_pixels"][0]["channel"] == "g");
  CHECK(diff["abs_error"]["max"].get<double>() == Approx(1e-3).epsilon(1e-9));
  CHECK(fs::file_size(dir.path / "art" / "error_heat_map.png") > 0);
  const std::string junit = junit_failures(dir.path / "j.xml");
  INFO(junit);
  CHECK(junit.rfind("OK 4 2", 0) == 0);  // pixels_within_tolerance and pixel(9,4)
  CHECK(junit.find("pixel(9,4) | pixel(9,4) channel g") != std::string::npos);
  CHECK(junit.find("factor") != std::string::npos);
  // The worst pixel's case file, evaluated by `exact`, gives the exact image's value bit for bit.
  const auto e = run_cli(dir.path, "eval art/worst_pixel_0.json --methods exact --no-timing");
  INFO(e.err);
  REQUIRE(e.status == 0);
  const auto ev = nlohmann::json::parse(e.out);
  const double replay = ev["cases"][0]["rays"][0]["methods"]["exact"]["intensity"][1].get<double>();
  CHECK(replay == expected);
}

TEST_CASE("CLI: bad candidate images exit 2 with one line and no output", "[image]") {
  TempDir dir;
  dir.write("cam.json", kCameraCase);
  write_image((dir.path / "small.npy").string(), test_image(12, 16));  // transposed size
  dir.write("junk.exr", "not an exr");
  const auto before = dir.entries();
  for (const std::string args : {"check cam.json --candidate-image small.npy --junit j.xml -o d.json",
                                 "check cam.json --candidate-image junk.exr --junit j.xml -o d.json",
                                 "check cam.json --candidate-image missing.pfm --junit j.xml -o d.json",
                                 "check cam.json --candidate-image cam.tiff --junit j.xml -o d.json"}) {
    INFO(args);
    CHECK(check_refused(dir, args).out.empty());
  }
  CHECK(run_cli(dir.path, "check cam.json --candidate-image small.npy").err.find("16 x 12") != std::string::npos);
  const auto unknown = run_cli(dir.path, "render cam.json -o out.tiff --quiet");
  CHECK(unknown.status == 2);
  CHECK(dir.entries() == before);
}

TEST_CASE("CLI: render on a slab scene points to rayint slab --scene", "[image]") {
  TempDir dir;
  const std::string slab = (fs::path(RAYINT_SOURCE_DIR) / "cases" / "scenes" / "slab-disort-1b.json").string();
  const auto r = run_cli(dir.path, "render '" + slab + "' -o x.png");
  INFO(r.err);
  CHECK(r.status == 2);
  CHECK(line_count(r.err) == 1);
  CHECK(r.err.find("rayint slab --scene") != std::string::npos);
  CHECK(dir.entries().empty());
}

TEST_CASE("CLI: gate --junit and check --junit name the failing check with measured, limit, factor", "[image]") {
  TempDir dir;
  const std::string fig2 = (fs::path(RAYINT_SOURCE_DIR) / "cases" / "paper-figure-2.json").string();
  const std::string smooth = (fs::path(RAYINT_SOURCE_DIR) / "cases" / "smooth-convergence.json").string();
  dir.write("gates.json", R"({"corpus": {"cases": [")" + smooth + R"("], "methods": {
      "exact": {"max_rel_error": 1e-13},
      "riemann:n=4": {"max_rel_error": 1e-9}}}})");
  const auto g = run_cli(dir.path, "gate --config gates.json --junit g.xml --quiet");
  INFO(g.err);
  CHECK(g.status == 1);
  const std::string junit = junit_failures(dir.path / "g.xml");
  INFO(junit);
  CHECK(junit.rfind("OK 2 1", 0) == 0);
  CHECK(junit.find("corpus.smooth-convergence.riemann:n=4.max_rel_error |") != std::string::npos);
  CHECK(junit.find("limit 1e-09, factor ") != std::string::npos);
  // check --candidate --junit: one testcase per ray.
  dir.write("cand.json", R"({"case": "paper-figure-2", "rays": [{"intensity": [0, 0, 0]},
      {"intensity": [0, 0, 0]}, {"intensity": [0, 0, 0]}]})");
  const auto c = run_cli(dir.path, "check '" + fig2 + "' --candidate cand.json --junit c.xml -o d.json --no-reference");
  CHECK(c.status == 1);
  const std::string cj = junit_failures(dir.path / "c.xml");
  INFO(cj);
  CHECK(cj.rfind("OK 3 ", 0) == 0);
  CHECK(cj.find("ray[0] | ray[0] channel ") != std::string::npos);
}

namespace {

// rayint's own Monte Carlo images with a known mean: the volumetric path tracer
// (scattering/volume_path_tracer.hpp, delta tracking) on a homogeneous, purely absorbing box
// (albedo 0) in front of a background of 1. Each path escapes with probability
// T = exp(-sigma * chord), so a pixel's exact value is T, from the box clip alone.
struct AbsorberScene {
  ScatteringVolume volume;
  Camera camera;
  Image exact;
  AbsorberScene(int size, double sigma) {
    volume.density = VoxelGrid({2, 2, 2}, Vec3(-1, -1, -1), Vec3(2, 2, 2), std::vector<double>(8, 1.0));
    volume.extinction_per_density = sigma;
    volume.albedo = 0.0;
    volume.background = 1.0;
    camera.position = Vec3(0.4, 0.3, 3.0);
    camera.look_at = Vec3(0, 0, 0);
    camera.fov_deg = 45;
    camera.width = camera.height = size;
    exact = Image(size, size);
    const Bounds box{Vec3(-1, -1, -1), Vec3(1, 1, 1)};
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const ViewRay r = camera.ray_for_pixel(x, y);
        const RaySpan span = box.clip(r);
        const double chord = span.hit ? (span.t_exit - span.t_enter) * r.direction.norm() : 0.0;
        const double t = std::exp(-sigma * chord);
        exact.at(x, y) = {t, t, t};
      }
  }
  // The path tracer's image for `seed` as (mean, variance of the mean), grey in r, g, b;
  // `bias` multiplies the mean (a wrong renderer).
  std::pair<Image, Image> render(std::uint64_t seed, int spp, double bias = 1.0) const {
    PathTracerOptions o;
    o.samples_per_pixel = spp;
    o.seed = seed;
    o.threads = 2;
    const EstimateImage e = path_trace_image(volume, camera, o);
    Image mean(e.width, e.height), var(e.width, e.height);
    for (std::size_t i = 0; i < mean.pixels.size(); ++i) {
      const double m = e.mean[i] * bias, v = e.std_error[i] * e.std_error[i];
      mean.pixels[i] = {m, m, m};
      var.pixels[i] = {v, v, v};
    }
    return {mean, var};
  }
};

}  // namespace

TEST_CASE("z-test: false-failure rate on rayint's path tracer, and power against a 25% and a 3% bias", "[image][ztest]") {
  // Seeds: 200 by default; RAYINT_ZTEST_SEEDS=N measures on N (README figure).
  const char* env = std::getenv("RAYINT_ZTEST_SEEDS");
  const int seeds = env ? std::atoi(env) : 200;
  const int spp = 256;
  const AbsorberScene scene(24, 0.7);
  ZTestOptions o;  // alpha 0.01 (Holm), min_fraction 0.9975
  int false_failures = 0, any_rejection = 0, caught = 0, caught_small = 0;
  for (int s = 1; s <= seeds; ++s) {
    const auto [mean, var] = scene.render(static_cast<std::uint64_t>(s), spp);
    const ZTestResult z = z_test_images(scene.exact, mean, var, o);
    false_failures += z.pass ? 0 : 1;
    any_rejection += z.rejected > 0 ? 1 : 0;
    if (s <= 20) {
      const auto [bmean, bvar] = scene.render(static_cast<std::uint64_t>(s), spp, 1.25);
      caught += z_test_images(scene.exact, bmean, bvar, o).pass ? 0 : 1;
      const auto [smean, svar] = scene.render(static_cast<std::uint64_t>(s), spp, 1.03);
      caught_small += z_test_images(scene.exact, smean, svar, o).pass ? 0 : 1;
    }
  }
  WARN("z-test on " << seeds << " path-traced images (24 x 24, " << spp << " spp, absorbing box): "
                    << false_failures << " false failures, " << any_rejection
                    << " with at least one rejected pixel channel; a 25% bias caught " << caught
                    << " of 20, a 3% bias " << caught_small << " of 20");
  // Holm bounds P(any rejection) by alpha = 1 % for a correct renderer (if the normal
  // approximation held); allow the binomial 99.9 % upper range of 1 % of `seeds`.
  const double expected = 0.01 * seeds;
  CHECK(false_failures <= expected + 3.1 * std::sqrt(expected) + 3);
  CHECK(caught == 20);  // a 3% bias is ~0.3 sigma per pixel at 256 spp: not expected to be caught
}

TEST_CASE("CLI: check --candidate-variance runs the z-test and names it in JUnit", "[image]") {
  TempDir dir;
  dir.write("cam.json", kCameraCase);
  REQUIRE(run_cli(dir.path, "render cam.json -o exact.npy --quiet").status == 0);
  const Image exact = read_image((dir.path / "exact.npy").string());
  // A "Monte Carlo" candidate 1 sigma off in every channel (sigma^2 = 1e-6 per sample, 100
  // samples): every p = 0.32, nothing rejected. Then a 0.01 bias, 10 sigma: every test rejected.
  write_z_test_candidates(dir.path, exact, 1e-6, 1e-4, 1e-2);
  const auto ok = run_cli(dir.path, "check cam.json --candidate-image mc.npy --candidate-variance var.npy --samples 100 -o d.json --junit j.xml");
  INFO(ok.err);
  CHECK(ok.status == 0);
  const auto d = nlohmann::json::parse(slurp(dir.path / "d.json"));
  CHECK(d["decided_by"] == "z_test");
  CHECK(d["z_test"]["rejected"] == 0);
  CHECK(d["z_test"]["tests"] == 16 * 12 * 3);
  CHECK(d["z_test"]["min_p"].get<double>() == Approx(std::erfc(1.0 / std::sqrt(2.0))).epsilon(1e-6));
  const auto bad = run_cli(dir.path, "check cam.json --candidate-image biased.npy --candidate-variance var.npy --samples 100 -o d.json --junit j.xml");
  CHECK(bad.status == 1);
  const std::string junit = junit_failures(dir.path / "j.xml");
  INFO(junit);
  CHECK(junit.rfind("OK 1 1", 0) == 0);
  CHECK(junit.find("z_test_fraction_passing | fraction of pixel channels passing the z-test measured 0, limit 0.998") != std::string::npos);
  // A negative variance is bad input.
  Image var = read_image((dir.path / "var.npy").string());
  var.at(2, 3)[0] = -1.0;
  write_image((dir.path / "var.npy").string(), var);
  const auto neg = run_cli(dir.path, "check cam.json --candidate-image mc.npy --candidate-variance var.npy -o d2.json");
  CHECK(neg.status == 2);
  CHECK(neg.err.find("var.npy: pixel(2,3): variance must be finite and >= 0") != std::string::npos);
  CHECK_FALSE(fs::exists(dir.path / "d2.json"));
}

namespace {

// An RGBA .npy (float64, shape (H, W, 4)) written byte by byte as NumPy's format 1.0 lays it out.
void write_rgba_npy(const fs::path& file, const Image& rgb, const std::vector<double>& alpha) {
  std::string header = "{'descr': '<f8', 'fortran_order': False, 'shape': (" + std::to_string(rgb.height) +
                       ", " + std::to_string(rgb.width) + ", 4), }";
  header.append((64 - (10 + header.size() + 1) % 64) % 64, ' ');
  header.push_back('\n');
  std::string out("\x93NUMPY\x01\x00", 8);
  out.push_back(static_cast<char>(header.size() & 0xff));
  out.push_back(static_cast<char>(header.size() >> 8));
  out += header;
  auto put = [&](double v) { out.append(reinterpret_cast<const char*>(&v), sizeof v); };  // x86: little-endian
  for (std::size_t i = 0; i < alpha.size(); ++i) {
    for (int c = 0; c < 3; ++c) put(rgb.pixels[i][c]);
    put(alpha[i]);
  }
  std::ofstream(file, std::ios::binary) << out;
}

std::string with_background(std::string text, const std::string& background) {
  const std::string key = "\"background\": [0.05, 0.1, 0.2]";
  text.replace(text.find(key), key.size(), "\"background\": " + background);
  return text;
}

}  // namespace

TEST_CASE("CLI: check --candidate-alpha composites a premultiplied or straight RGBA candidate over the case's background", "[image][alpha]") {
  // Independent construction of the RGBA image: the exact image over a black background is the
  // emitted colour C, over white it is C + T (the case's density is shared by r, g, b), so
  // alpha = 1 - T. Composited over the case's own background it must equal the exact image
  // rendered over that background, which rayint computes on its own.
  TempDir dir;
  dir.write("cam.json", kCameraCase);
  dir.write("black.json", with_background(kCameraCase, "[0, 0, 0]"));
  dir.write("white.json", with_background(kCameraCase, "[1, 1, 1]"));
  for (const std::string c : {"cam", "black", "white"})
    REQUIRE(run_cli(dir.path, "render " + c + ".json -o " + c + ".npy --quiet").status == 0);
  const Image black = read_image((dir.path / "black.npy").string());
  const Image white = read_image((dir.path / "white.npy").string());
  const Image exact = read_image((dir.path / "cam.npy").string());
  std::vector<double> alpha(black.pixels.size());
  Image straight(black.width, black.height);
  std::size_t see_through = 0;
  for (std::size_t i = 0; i < alpha.size(); ++i) {
    alpha[i] = std::clamp(1.0 - (white.pixels[i][0] - black.pixels[i][0]), 0.0, 1.0);
    if (alpha[i] < 0.99) ++see_through;
    for (int c = 0; c < 3; ++c) straight.pixels[i][c] = alpha[i] > 0.0 ? black.pixels[i][c] / alpha[i] : 0.0;
  }
  REQUIRE(see_through > alpha.size() / 2);  // the background shows through: the test has teeth
  write_rgba_npy(dir.path / "premultiplied.npy", black, alpha);
  write_rgba_npy(dir.path / "straight.npy", straight, alpha);

  // Library: the composited images equal the exact one to rounding.
  const Rgb bg{0.05, 0.1, 0.2};
  const Image pre = composite_over(black, alpha, bg, AlphaMode::premultiplied);
  const Image str = composite_over(straight, alpha, bg, AlphaMode::straight);
  double worst = 0.0;
  for (std::size_t i = 0; i < alpha.size(); ++i)
    for (int c = 0; c < 3; ++c)
      worst = std::max({worst, std::fabs(pre.pixels[i][c] - exact.pixels[i][c]),
                        std::fabs(str.pixels[i][c] - exact.pixels[i][c])});
  CHECK(worst <= 1e-14);

  // CLI: passes with the right --candidate-alpha at 1e-12, fails when the alpha is ignored.
  for (const std::string mode : {"premultiplied", "straight"}) {
    INFO(mode);
    const auto r = run_cli(dir.path, "check cam.json --candidate-image " + mode + ".npy --candidate-alpha " + mode +
                                         " --rel-tol 1e-12 --abs-tol 1e-14 -o d.json");
    INFO(r.err);
    CHECK(r.status == 0);
    const auto diff = nlohmann::json::parse(slurp(dir.path / "d.json"));
    CHECK(diff["candidate_alpha"].get<std::string>().rfind(mode, 0) == 0);
  }
  const auto ignored = run_cli(dir.path, "check cam.json --candidate-image premultiplied.npy --rel-tol 1e-12 -o d.json");
  CHECK(ignored.status == 1);

  // Bad input: no alpha channel, alpha outside [0, 1], unknown mode: exit 2, one line, no output.
  alpha[5] = 1.5;
  write_rgba_npy(dir.path / "bad_alpha.npy", black, alpha);
  for (const std::string args : {"check cam.json --candidate-image cam.npy --candidate-alpha premultiplied -o o.json",
                                 "check cam.json --candidate-image bad_alpha.npy --candidate-alpha straight -o o.json",
                                 "check cam.json --candidate-image premultiplied.npy --candidate-alpha other -o o.json"})
    check_refused(dir, args);
  CHECK(run_cli(dir.path, "check cam.json --candidate-image cam.npy --candidate-alpha premultiplied").err.find("no alpha channel") !=
        std::string::npos);
  CHECK(run_cli(dir.path, "check cam.json --candidate-image bad_alpha.npy --candidate-alpha straight").err.find("pixel(5,0)") !=
        std::string::npos);
}
