// `rayint check SCENE --candidate-image IMAGE` (cli/check_image.cpp): a renderer's image of a
// scene against the scene's reference image (scene/pipeline.hpp ScenePipeline::reference_image).
// The candidate that passes is rayint render's own image, computed by the scene's methods
// (`exact` for absorption and emission on a piecewise-linear medium), an independent path from
// the references (adaptive Gauss-Kronrod to rtol 1e-9).
#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "test_paths.hpp"
#include "candidate_images.hpp"
#include "cli_harness.hpp"
#include "rayint/render/float_image.hpp"

namespace {

using namespace rayint;
using namespace rayint::test;
using nlohmann::json;

// A 12 x 10 camera (not square) on a box of constant density, emission and absorption, over a
// constant background.
const std::string kScene = R"({
  "name": "box-scene",
  "medium": {"type": "homogeneous", "shape": "box", "density": 0.8, "lower": [-0.6, -0.5, -0.4], "upper": [0.6, 0.5, 0.4]},
  "transfer": {"extinction": [[0, 0], [1, 3]], "emission": {"r": [[0, 0.9]], "g": [[0, 0.4]], "b": [[0, 0.2]]}},
  "camera": {"position": [0.4, 0.3, 3.0], "look_at": [0, 0, 0], "fov_deg": 40, "width": 12, "height": 10},
  "background": {"color": [0.1, 0.2, 0.4]},
  "effects": ["absorption", "emission"]
})";

}  // namespace

TEST_CASE("scene image check: the scene's own render passes, one pixel off by 1e-3 fails and replays", "[image][scene]") {
  TempDir dir;
  dir.write("scene.json", kScene);
  const CliRun rr = run_cli_ok(dir.path, "render scene.json -o render.npy --quiet --threads 2");
  fs::create_directories(dir.path / "art");
  const CliRun ok = run_cli(dir.path, "check scene.json --candidate-image render.npy --artifacts art -o diff.json --threads 2");
  INFO(ok.err);
  CHECK(ok.status == 0);
  const json d = json::parse(slurp(dir.path / "diff.json"));
  CHECK(d["pass"] == true);
  CHECK(d["scene_file"] == "scene.json");
  CHECK(d["width"] == 12);
  CHECK(d["height"] == 10);
  CHECK(d["rel_error"]["max"].get<double>() < 1e-8);   // exact vs a reference to rtol 1e-9
  CHECK(d["reference"]["unconverged_pixels"] == 0);
  CHECK(d["reference"]["max_error_estimate"].get<double>() < 1e-8);
  // The reference image, written to the artifacts, passes its own check with no error at all.
  const CliRun self = run_cli(dir.path, "check scene.json --candidate-image art/reference.npy --artifacts art -o self.json");
  CHECK(self.status == 0);
  CHECK(json::parse(slurp(dir.path / "self.json"))["abs_error"]["max"].get<double>() == 0.0);

  // One pixel off by 1e-3 in green.
  Image im = read_image((dir.path / "render.npy").string());
  im.at(7, 3)[1] += 1e-3;
  write_image((dir.path / "off.npy").string(), im);
  const CliRun bad = run_cli(dir.path, "check scene.json --candidate-image off.npy --artifacts art -o diff.json --junit j.xml");
  INFO(bad.err);
  CHECK(bad.status == 1);
  const json b = json::parse(slurp(dir.path / "diff.json"));
  CHECK(b["pass"] == false);
  CHECK(b["failed_pixels"] == 1);
  const json& w = b["worst_pixels"][0];
  CHECK(w["x"] == 7);
  CHECK(w["y"] == 3);
  CHECK(w["channel"] == "g");
  CHECK(w["abs_error"].get<double>() == Approx(1e-3).epsilon(1e-6));
  CHECK(slurp(dir.path / "j.xml").find("pixel(7,3)") != std::string::npos);
  CHECK(fs::file_size(dir.path / "art" / "error_heat_map.png") > 0);

  // The worst pixel as a scene with that pixel's ray: its check on a 1 x 1 image holding the
  // candidate's pixel fails the same way, against the same reference value.
  const std::string pixel_scene = w["scene_file"].get<std::string>();
  CHECK(pixel_scene == "art/worst_pixel_0.json");
  const json ps = json::parse(slurp(dir.path / pixel_scene));
  CHECK_FALSE(ps.contains("camera"));
  CHECK(ps["rays"].size() == 1);
  Image one(1, 1);
  one.at(0, 0) = im.at(7, 3);
  write_image((dir.path / "one.npy").string(), one);
  const CliRun replay = run_cli(dir.path, "check art/worst_pixel_0.json --candidate-image one.npy --artifacts art -o replay.json");
  INFO(replay.err);
  CHECK(replay.status == 1);
  const json rp = json::parse(slurp(dir.path / "replay.json"));
  CHECK(rp["worst_pixels"][0]["channel"] == "g");
  CHECK(rp["worst_pixels"][0]["expected"].get<double>() == Approx(w["expected"].get<double>()).epsilon(1e-12));
  // And rendered by the scene's methods it gives the pixel of the full render.
  run_cli_ok(dir.path, "render art/worst_pixel_0.json -o one_render.npy --quiet");
  const Image r1 = read_image((dir.path / "one_render.npy").string());
  const Image full = read_image((dir.path / "render.npy").string());
  for (int c = 0; c < 3; ++c) CHECK(r1.at(0, 0)[c] == Approx(full.at(7, 3)[c]).epsilon(1e-12));
}

TEST_CASE("scene image check: z-test mode, wrong size and slab scenes", "[image][scene]") {
  TempDir dir;
  dir.write("scene.json", kScene);
  fs::create_directories(dir.path / "art");
  run_cli_ok(dir.path, "render scene.json -o render.npy --quiet");
  run_cli_ok(dir.path, "check scene.json --candidate-image render.npy --artifacts art -o d.json");
  const Image ref = read_image((dir.path / "art" / "reference.npy").string());
  // 1 sigma off everywhere (variance of the mean 1e-8): passes; 10 sigma: fails.
  write_z_test_candidates(dir.path, ref, 1e-8, 1e-4, 1e-3);
  const CliRun pass = run_cli(dir.path, "check scene.json --candidate-image mc.npy --candidate-variance var.npy --artifacts art -o z.json");
  INFO(pass.err);
  CHECK(pass.status == 0);
  const json z = json::parse(slurp(dir.path / "z.json"));
  CHECK(z["decided_by"] == "z_test");
  CHECK(z["z_test"]["rejected"] == 0);
  CHECK(z["reference"].contains("z_test"));
  CHECK(run_cli(dir.path, "check scene.json --candidate-image biased.npy --candidate-variance var.npy --artifacts art -o z.json").status == 1);

  // A candidate of the wrong size: exit 2, one line naming the image and the scene's camera.
  write_image((dir.path / "small.npy").string(), Image(4, 3));
  const CliRun small = run_cli(dir.path, "check scene.json --candidate-image small.npy --artifacts art -o s.json");
  CHECK(small.status == 2);
  CHECK(small.err.find("small.npy: (image): 4 x 3 pixels, the camera of scene.json has 12 x 10") != std::string::npos);
  CHECK(line_count(small.err) == 1);
  CHECK_FALSE(fs::exists(dir.path / "s.json"));
  // A slab scene is not an image.
  const std::string slab = (fs::path(RAYINT_SOURCE_DIR) / "cases" / "scenes" / "slab-disort-1b.json").string();
  const CliRun sl = run_cli(dir.path, "check '" + slab + "' --candidate-image render.npy");
  CHECK(sl.status == 2);
  CHECK(sl.err.find("rayint slab --scene") != std::string::npos);
}
