// `rayint grad` and `rayint gradcheck` (issue 28): the JSON layout, an exact candidate passes,
// a wrong one fails naming its worst entry, bad input is one line and exit 2.
#include <nlohmann/json.hpp>
#include <cmath>
#include <filesystem>
#include <cstring>
#include <string>
#include <vector>

#include "test_paths.hpp"
#include "cli_harness.hpp"
#include "rayint/input/candidate_reader.hpp"
#include "rayint/render/float_image.hpp"
#include "tolerances.hpp"

using rayint::test::run_cli;
using rayint::test::slurp;
using rayint::test::TempDir;
using nlohmann::json;

namespace {

// A gradcheck candidate from `rayint grad` output: method `label` of the first case.
std::string candidate_from(const json& report, const std::string& label) {
  json cand = {{"case", report["cases"][0]["case"]}, {"renderer", label}, {"rays", json::array()}};
  for (const json& ray : report["cases"][0]["rays"])
    cand["rays"].push_back({{"gradient", ray["methods"][label]["gradient"]}});
  return cand.dump();
}

}  // namespace

TEST_CASE("grad: layout of the issue, reference and errors per method", "[grad][grad_cli]") {
  TempDir dir;
  dir.copy_case("paper-figure-2");
  const auto r = run_cli(dir.path, "grad paper-figure-2.json --methods exact,riemann:n=16,ode -o g.json");
  REQUIRE(r.status == 0);
  const json j = json::parse(slurp(dir.path / "g.json"));
  const json& ray1 = j["cases"][0]["rays"][1];
  const json& g = ray1["methods"]["exact"]["gradient"];
  CHECK(g["background"].size() == 3);
  CHECK(g["length"].size() == 2);  // ray 1 has two segments
  CHECK(g["scalar"].size() == 2);
  CHECK(g["scalar"][0].size() == 2);
  CHECK(g["scalar"][0][0].size() == 3);
  CHECK(g["density"]["r"].size() == 2);  // the case's density has two nodes
  CHECK(g["density"]["r"][0].size() == 2);
  CHECK(g["color"]["b"].size() == 2);
  CHECK(ray1["reference"]["gradient"]["length"].size() == 2);
  // exact against the 50-digit reference: within the tested tolerance.
  for (int c = 0; c < 3; ++c)
    CHECK(ray1["methods"]["exact"]["errors"]["gradient_max_rel_vs_reference"][c].get<double>() <= 1e-14);
  // riemann n=16 has an error; ode has no gradient and is shown failed, not as a number.
  CHECK(ray1["methods"]["riemann:n=16"]["errors"]["gradient_max_rel_vs_reference"][0].get<double>() > 1e-8);
  CHECK(ray1["methods"]["ode"]["gradient"].is_null());
  CHECK(ray1["methods"]["ode"]["error"].get<std::string>().find("no gradient") != std::string::npos);
}

TEST_CASE("gradcheck: the exact candidate passes, a perturbed entry and Riemann n=16 fail by name", "[grad][grad_cli]") {
  TempDir dir;
  dir.copy_case("paper-figure-2");
  REQUIRE(run_cli(dir.path, "grad paper-figure-2.json --no-reference --methods exact,riemann:n=16 -o g.json").status == 0);
  const json report = json::parse(slurp(dir.path / "g.json"));
  dir.write("exact.json", candidate_from(report, "exact"));
  dir.write("riemann.json", candidate_from(report, "riemann:n=16"));
  json wrong = json::parse(candidate_from(report, "exact"));
  double& entry = wrong["rays"][1]["gradient"]["color"]["g"][1][1].get_ref<double&>();
  entry *= 1.001;
  dir.write("wrong.json", wrong.dump());

  const auto ok = run_cli(dir.path, "gradcheck paper-figure-2.json --candidate exact.json --rel-tol 1e-12");
  CHECK(ok.status == 0);
  CHECK(json::parse(ok.out)["pass"] == true);

  const auto bad = run_cli(dir.path, "gradcheck paper-figure-2.json --candidate wrong.json --rel-tol 1e-6 --junit j.xml");
  CHECK(bad.status == 1);
  CHECK(bad.err.find("worst: ray 1 color node 1 value channel g") != std::string::npos);
  CHECK(json::parse(bad.out)["failed"] == 1);
  CHECK(slurp(dir.path / "j.xml").find("<failure") != std::string::npos);

  const auto rie = run_cli(dir.path, "gradcheck paper-figure-2.json --candidate riemann.json --rel-tol 1e-6");
  CHECK(rie.status == 1);
  CHECK(rie.err.find("FAIL") != std::string::npos);
  CHECK(rie.err.find("worst: ray ") != std::string::npos);
}

// tests/fixtures/gradients/narrow-pulse-ray-1468.json: a narrow_pulse ray (reports/gradients,
// gradchain_rays.hpp ray 1468) whose density-ramp nodes are 20 ulps apart. There the analytic
// exact gradient is 6.1e-3 of channel r's largest entry from the 50-digit reference, and an
// independent 90-digit mpmath computation (reports/gradients/narrow_pulse_conditioning.py) agrees
// with the reference: dI_r/d(density node 3 position) = 0.0260569040563 (exact: 0.02147886).
TEST_CASE("gradcheck --reference: the truth passes where the exact gradient is ill-conditioned", "[grad][grad_cli]") {
  TempDir dir;
  std::filesystem::copy_file(std::filesystem::path(RAYINT_SOURCE_DIR) / "tests/fixtures/gradients/narrow-pulse-ray-1468.json",
                dir.path / "np.json");
  REQUIRE(run_cli(dir.path, "grad np.json -o g.json").status == 0);
  const json report = json::parse(slurp(dir.path / "g.json"));
  json truth = {{"case", "np1468"}, {"renderer", "50-digit reference"}, {"rays", json::array()}};
  truth["rays"].push_back({{"gradient", report["cases"][0]["rays"][0]["reference"]["gradient"]}});
  const double ref_entry = truth["rays"][0]["gradient"]["density"]["r"][3][0].get<double>();
  CHECK(std::fabs(ref_entry - 0.0260569040563) < 1e-12);  // the mpmath value, not rayint's
  dir.write("truth.json", truth.dump());
  dir.write("exact.json", candidate_from(report, "exact"));

  // Against the analytic exact gradient a candidate holding the true values fails ...
  const auto vs_exact = run_cli(dir.path, "gradcheck np.json --candidate truth.json --rel-tol 1e-4");
  CHECK(vs_exact.status == 1);
  CHECK(vs_exact.err.find("worst: ray 0 density node 3 position channel r") != std::string::npos);
  // ... and passes against the reference, which names the exact gradient's own distance.
  const auto vs_ref = run_cli(dir.path, "gradcheck np.json --candidate truth.json --rel-tol 1e-9 --reference");
  CHECK(vs_ref.status == 0);
  const json verdict = json::parse(vs_ref.out);
  CHECK(verdict["against"] == "reference");
  CHECK(verdict["exact_vs_reference"][0].get<double>() > 1e-3);
  CHECK(vs_ref.err.find("exact vs reference (largest per channel): r ") != std::string::npos);
  // The exact gradient as a candidate: passes against itself, fails against the reference.
  CHECK(run_cli(dir.path, "gradcheck np.json --candidate exact.json --rel-tol 1e-12").status == 0);
  const auto exact_vs_ref = run_cli(dir.path, "gradcheck np.json --candidate exact.json --rel-tol 1e-4 --reference");
  CHECK(exact_vs_ref.status == 1);
  CHECK(exact_vs_ref.err.find("reference 0.0260569040") != std::string::npos);
  CHECK(json::parse(run_cli(dir.path, "gradcheck np.json --candidate exact.json").out)["exact_vs_reference"].is_null());
}

TEST_CASE("gradcheck: bad input is one line naming the file and field, exit 2", "[grad][grad_cli]") {
  TempDir dir;
  dir.copy_case("paper-figure-2");
  dir.write("nan.json", R"({"case": "paper-figure-2", "rays": [{"gradient": {"background": [1, "x", 0]}}]})");
  const auto r = run_cli(dir.path, "gradcheck paper-figure-2.json --candidate nan.json");
  CHECK(r.status == 2);
  CHECK(r.out.empty());
  CHECK(rayint::test::line_count(r.err) == 1);
  CHECK(r.err.find("nan.json: rays[0].gradient") != std::string::npos);
  dir.write("short.json", R"({"case": "paper-figure-2", "rays": [{"gradient": {"background": [1, 1, 0]}}]})");
  const auto s = run_cli(dir.path, "gradcheck paper-figure-2.json --candidate short.json");
  CHECK(s.status == 2);
  CHECK(s.err.find("short.json: rays[0].gradient") != std::string::npos);
}

TEST_CASE("grad candidate reader: shape mismatches name the field", "[grad]") {
  rayint::Case c;
  c.name = "x";
  c.source = "x.json";
  for (int ch = 0; ch < 3; ++ch) {
    c.transfer.density[ch] = {{0.0, 1.0}, {1.0, 2.0}};
    c.transfer.color[ch] = {{0.0}, {1.0}};
  }
  c.rays.resize(1);
  c.rays[0].segments.resize(1);
  const std::string good =
      R"({"case": "x", "rays": [{"gradient": {"background": [1, 1, 1], "length": [[0, 0, 0]], )"
      R"("scalar": [[[0, 0, 0], [0, 0, 0]]], "density": {"r": [[0, 0], [0, 0]], "g": [[0, 0], [0, 0]], )"
      R"("b": [[0, 0], [0, 0]]}, "color": {"r": [[0, 1]], "g": [[0, 1]], "b": [[0, 1]]}}}]})";
  const rayint::GradCandidate cand = rayint::parse_grad_candidate_text(good, "c.json");
  CHECK_NOTHROW(rayint::require_grad_candidate_matches(cand, c));
  c.transfer.color[1] = {{0.0, 1.0}, {1.0, 1.0}};
  CHECK_THROWS_WITH(rayint::require_grad_candidate_matches(cand, c),
                    Catch::Contains("c.json: rays[0].gradient.color.g: has 1 nodes"));
}

TEST_CASE("render --loss-target --grad-out: the loss gradient as NPY, zero at its own image, bad input", "[grad][grad_cli]") {
  TempDir dir;
  const std::string mesh_case = "'" + RAYINT_SOURCE_DIR + "/cases/mesh-linear-field.json'";
  REQUIRE(run_cli(dir.path, "render " + mesh_case + " -o own.npy -q").status == 0);
  // Against its own exact render (the batch path; the gradient's forward equals it to rounding): residuals ~1e-16, so the loss ~1e-30 and the gradient ~1e-15 (against ~40 below).
  auto r = run_cli(dir.path, "render " + mesh_case + " -o fit.npy --loss-target own.npy --grad-out g.npy "
                   "--grad-positions-out gp.npy -q");
  REQUIRE(r.status == 0);
  const auto loss_of = [](const std::string& err) {
    const std::string key = "rayint render: loss ";
    const auto at = err.find(key);
    return at == std::string::npos ? -1.0 : std::stod(err.substr(at + key.size()));
  };
  CHECK(r.err.find(" over 128 x 128 pixels; d loss / d vertex scalar -> g.npy (343 values)") != std::string::npos);
  CHECK(loss_of(r.err) >= 0.0);
  CHECK(loss_of(r.err) < 1e-25);
  const auto values = [](const std::string& npy) {
    const std::size_t header = 10 + static_cast<unsigned char>(npy[8]) + 256u * static_cast<unsigned char>(npy[9]);
    std::vector<double> v((npy.size() - header) / 8);
    std::memcpy(v.data(), npy.data() + header, v.size() * 8);
    return std::make_pair(npy.substr(10, header - 10), v);
  };
  const std::string g = slurp(dir.path / "g.npy");
  REQUIRE(g.size() > 128);
  const auto [g_header, g_values] = values(g);
  CHECK(g_header.find("'shape': (343,)") != std::string::npos);  // one per point
  REQUIRE(g_values.size() == 343);
  double g_max = 0.0;
  for (double v : g_values) g_max = std::max(g_max, std::fabs(v));
  CHECK(g_max < 1e-10);
  CHECK(slurp(dir.path / "gp.npy").find("'shape': (343, 3)") != std::string::npos);
  // A different target: a non-zero loss and gradient (the values are tested in [grad][mesh]).
  dir.write("grey.npy", rayint::encode_npy(rayint::Image(128, 128, rayint::Rgb{0.5, 0.5, 0.5})));
  r = run_cli(dir.path, "render " + mesh_case + " -o fit2.npy --loss-target grey.npy --grad-out g2.npy -q");
  CHECK(r.status == 0);
  CHECK(loss_of(r.err) > 1.0);
  double g2_max = 0.0;
  for (double v : values(slurp(dir.path / "g2.npy")).second) g2_max = std::max(g2_max, std::fabs(v));
  CHECK(g2_max > 1.0);
  // Bad input: one line, exit 2, nothing written.
  TempDir bad;
  r = run_cli(bad.path, "render " + mesh_case + " -o x.npy --grad-out g.npy");
  CHECK(r.status == 2);
  CHECK(r.err == "rayint: error: --grad-out and --loss-target go together (--grad-positions-out needs both)\n");
  bad.write("t.png", "not read");
  r = run_cli(bad.path, "render " + mesh_case + " -o x.npy --loss-target t.png --grad-out g.npy");
  CHECK(r.status == 2);
  CHECK(r.err.find("t.png: --loss-target: a float image is needed") != std::string::npos);
  CHECK(bad.entries() == std::set<std::string>{"t.png"});
}

TEST_CASE("grad: a transfer function from a ParaView preset names where its nodes come from", "[grad][grad_cli]") {
  TempDir dir;
  dir.write("preset.json", R"([{"Name": "lin", "ColorSpace": "RGB",
    "RGBPoints": [0, 0.1, 0.2, 0.9, 0.5, 0.8, 0.3, 0.2, 1, 0.9, 0.6, 0.5]}])");
  dir.write("case.json", R"({"name": "preset-grad", "transfer_function": {"paraview_preset": "preset.json",
    "name": "lin", "opacity": 0.8}, "rays": [{"background": [0, 0, 0], "segments": [
    {"length": 0.7, "scalar": [0.1, 0.9]}, {"length": 0.4, "scalar": [0.9, 0.3]}]}]})");
  const auto r = run_cli(dir.path, "grad case.json --no-reference -o g.json");
  REQUIRE(r.status == 0);
  const json j = json::parse(slurp(dir.path / "g.json"));
  const json& c = j["cases"][0];
  REQUIRE(c.contains("transfer_function_nodes"));
  CHECK(c["transfer_function_nodes"]["imported_from"] == "ParaView preset \"lin\" of preset.json");
  CHECK(c["rays"][0]["methods"]["exact"]["gradient"]["color"]["r"].size() >= 3);  // the imported nodes
  // A case with its own nodes has no such entry.
  dir.copy_case("paper-figure-2");
  const auto r2 = run_cli(dir.path, "grad paper-figure-2.json --no-reference -o g2.json");
  REQUIRE(r2.status == 0);
  CHECK_FALSE(json::parse(slurp(dir.path / "g2.json"))["cases"][0].contains("transfer_function_nodes"));
}

TEST_CASE("grad: a preset case carries the gradient w.r.t. the preset's own points, or why not", "[grad][grad_cli]") {
  TempDir dir;
  // RGB with default midpoints: the imported colour nodes are the RGBPoints themselves, so
  // dI_r/dr_k must equal the colour node k's value derivative (an independent plumbing check).
  dir.write("rgb.json", R"([{"Name": "lin", "ColorSpace": "RGB",
    "RGBPoints": [0, 0.1, 0.2, 0.9, 0.5, 0.8, 0.3, 0.2, 1, 0.9, 0.6, 0.5],
    "Points": [0, 0.1, 0.5, 0, 0.45, 0.6, 0.5, 0, 1, 0.3, 0.5, 0]}])");
  dir.write("case.json", R"({"name": "preset-points", "transfer_function": {"paraview_preset": "rgb.json",
    "unit_distance": 2}, "rays": [{"background": [0.2, 0.1, 0], "segments": [
    {"length": 0.7, "scalar": [0.1, 0.9]}, {"length": 0.4, "scalar": [0.9, 0.3]}]}]})");
  auto r = run_cli(dir.path, "grad case.json --no-reference --methods exact,riemann:n=8 -o g.json");
  REQUIRE(r.status == 0);
  json j = json::parse(slurp(dir.path / "g.json"));
  const json& m = j["cases"][0]["rays"][0]["methods"]["exact"];
  const json& pg = m["preset_gradient"];
  REQUIRE(pg["RGBPoints"].is_object());
  REQUIRE(pg["RGBPoints"]["r"].size() == 3);
  REQUIRE(pg["Points"]["g"].size() == 3);
  for (std::size_t k = 0; k < 3; ++k) {
    CHECK(pg["RGBPoints"]["r"][k][1].get<double>() == m["gradient"]["color"]["r"][k][1].get<double>());
    CHECK(pg["RGBPoints"]["r"][k][2].get<double>() == 0.0);  // I_r does not depend on green
    // rho = opacity / 2 under unit_distance 2: dI/dopacity = dI/drho / 2.
    CHECK(pg["Points"]["b"][k][1].get<double>() == Approx(m["gradient"]["density"]["b"][k][1].get<double>() / 2));
  }
  CHECK(j["cases"][0]["rays"][0]["methods"]["riemann:n=8"].contains("preset_gradient"));
  // An HSV interval is linearised adaptively: no numbers for RGBPoints, a reason.
  dir.write("hsv.json", R"([{"Name": "hsv", "ColorSpace": "HSV",
    "RGBPoints": [0, 0.1, 0.2, 0.9, 0.5, 0.8, 0.3, 0.2, 1, 0.9, 0.6, 0.5]}])");
  dir.write("case2.json", R"({"name": "hsv", "transfer_function": {"paraview_preset": "hsv.json",
    "name": "hsv", "opacity": 0.8}, "rays": [{"background": [0, 0, 0], "segments": [
    {"length": 0.7, "scalar": [0.1, 0.9]}]}]})");
  r = run_cli(dir.path, "grad case2.json --no-reference -o g2.json");
  REQUIRE(r.status == 0);
  j = json::parse(slurp(dir.path / "g2.json"));
  const json& pg2 = j["cases"][0]["rays"][0]["methods"]["exact"]["preset_gradient"];
  CHECK(pg2["RGBPoints"].is_null());
  CHECK(pg2["RGBPoints_unavailable"].get<std::string>().find("adaptively") != std::string::npos);
  CHECK(pg2["Points"].is_null());  // a constant opacity was given
}

TEST_CASE("grad: Cool to Warm, imported with jumps at its end nodes, is differentiated and matches the reference",
          "[grad][grad_cli][grad_jump]") {
  TempDir dir;
  // "Cool to Warm" (Diverging) imports with jumps of ~3e-5 at its two end nodes, where VTK's
  // node colour and its Diverging interpolation differ. Ray 0 stays inside the range; ray 1
  // crosses the jump at 0 twice, ray 2 the one at 1 once; ray 3 ends exactly on the jump at 1,
  // where the derivative in that jump's position and in the ray's last scalar does not exist.
  // (The import has ~1200 nodes per colour function: the rays are kept short in the scalar so
  // that the 50-digit reference differences a few dozen of them.)
  dir.write("cw.json", slurp(RAYINT_SOURCE_DIR + "/fuzz/seeds/preset/colormap-0.json"));
  dir.write("case.json", R"({"name": "cw", "transfer_function": {"paraview_preset": "cw.json",
    "name": "Cool to Warm", "opacity": 0.8}, "rays": [
    {"background": [0.1, 0.2, 0.3], "segments": [{"length": 0.7, "scalar": [0.40, 0.42]}]},
    {"background": [0.1, 0.2, 0.3], "segments": [{"length": 0.7, "scalar": [-0.05, 0.02]}, {"length": 1.4, "scalar": [0.02, -0.03]}]},
    {"background": [0.1, 0.2, 0.3], "segments": [{"length": 2.5, "scalar": [0.98, 1.03]}]},
    {"background": [0.1, 0.2, 0.3], "segments": [{"length": 0.7, "scalar": [0.99, 1]}]}]})");
  const auto r = run_cli(dir.path, "grad case.json --threads 2 -o g.json");
  REQUIRE(r.status == 0);
  const json j = json::parse(slurp(dir.path / "g.json"));
  const json& c = j["cases"][0];
  REQUIRE(c["transfer_function_nodes"]["imported_from"].get<std::string>().find("Cool to Warm") != std::string::npos);
  for (int i = 0; i < 4; ++i) {
    const json& m = c["rays"][i]["methods"]["exact"];
    INFO("ray " << i);
    for (const auto& e : m["errors"]["gradient_max_rel_vs_reference"]) {
      REQUIRE(e.is_number());
      CHECK(e.get<double>() <= rayint::test::GradTolerances::jump_vs_reference_rel);
    }
    // The colour functions jump at their first and last nodes: the tie (second node 0).
    const json& red = m["gradient"]["color"]["r"];
    REQUIRE(red.size() >= 4);
    if (i == 1) {
      CHECK(red[0][0].get<double>() != 0.0);  // the jump at 0, crossed twice
      CHECK(red[1][0].get<double>() == 0.0);
    }
    // The preset's own points: Diverging is linearised adaptively, so not mapped, with the reason.
    CHECK(m["preset_gradient"]["RGBPoints"].is_null());
  }
  // Ray 3 ends on the jump at 1: null entries with the reason, in exact and in the reference alike.
  const json& m2 = c["rays"][3]["methods"]["exact"];
  CHECK(m2["gradient"].contains("undefined"));
  CHECK(m2["gradient"]["scalar"][0][1][0].is_null());
  const json& last = m2["gradient"]["color"]["r"];
  CHECK(last[last.size() - 2][0].is_null());
  CHECK(c["rays"][3]["reference"]["gradient"]["scalar"][0][1][0].is_null());
  const json& last2 = c["rays"][2]["methods"]["exact"]["gradient"]["color"]["r"];
  CHECK(last2[last2.size() - 2][0].get<double>() != 0.0);  // the jump at 1, crossed
  CHECK(last2[last2.size() - 1][0].get<double>() == 0.0);
  CHECK_FALSE(c["rays"][0]["methods"]["exact"]["gradient"].contains("undefined"));
}

TEST_CASE("gradcheck across a jump: the tie, untested null entries, a candidate without the jump term fails",
          "[grad][grad_cli][grad_jump]") {
  TempDir dir;
  // Density jumps 0.6 -> 2.5 at 0.5 (both nodes at 0.5). Ray 0 crosses it twice; ray 1 ends on it.
  dir.write("case.json", R"({"name": "jump", "transfer_function": {
    "density": [[0.2, 0.4], [0.5, 0.6], [0.5, 2.5], [0.9, 1.0]], "color": [[0.0, 0.2], [1.0, 0.9]]},
    "rays": [{"background": [0.1, 0.2, 0.3], "segments": [{"length": 1.0, "scalar": [0.3, 0.8]}, {"length": 0.6, "scalar": [0.8, 0.35]}]},
             {"background": [0.1, 0.2, 0.3], "segments": [{"length": 1.0, "scalar": [0.1, 0.5]}]}]})");
  REQUIRE(run_cli(dir.path, "grad case.json --no-reference -o g.json").status == 0);
  const json report = json::parse(slurp(dir.path / "g.json"));
  json cand = json::parse(candidate_from(report, "exact"));
  // Ray 1's null entries (no derivative exists) get a number: not checked, counted.
  json& g1 = cand["rays"][1]["gradient"];
  REQUIRE(g1["density"]["r"][1][0].is_null());
  for (const char* ch : {"r", "g", "b"}) g1["density"][ch][1][0] = 0.0;
  for (int c = 0; c < 3; ++c) g1["scalar"][0][1][c] = 0.0;
  g1.erase("undefined");
  cand["rays"][0]["gradient"].erase("undefined");
  dir.write("exact.json", cand.dump());
  const auto ok = run_cli(dir.path, "gradcheck case.json --candidate exact.json --rel-tol 1e-12");
  CHECK(ok.status == 0);
  const json verdict = json::parse(ok.out);
  CHECK(verdict["undefined"].get<int>() == 6);  // 3 channels x (jump position, ray end scalar)
  CHECK(ok.err.find("6 entries skipped, undefined") != std::string::npos);
  CHECK(verdict["null_in_candidate"].get<int>() == 0);
  // The same with the candidate leaving them null: skipped too (not counted as null entries).
  json with_nulls = json::parse(candidate_from(report, "exact"));
  with_nulls["rays"][0]["gradient"].erase("undefined");
  with_nulls["rays"][1]["gradient"].erase("undefined");
  dir.write("nulls.json", with_nulls.dump());
  const auto skipped = run_cli(dir.path, "gradcheck case.json --candidate nulls.json --rel-tol 1e-12");
  CHECK(skipped.status == 0);
  CHECK(json::parse(skipped.out)["undefined"].get<int>() == 6);
  CHECK(json::parse(skipped.out)["null_in_candidate"].get<int>() == 0);
  // A candidate with the other tie (the jump's derivative on the second node) fails, by name.
  json wrong = cand;
  const double tied = wrong["rays"][0]["gradient"]["density"]["r"][1][0].get<double>();
  REQUIRE(tied != 0.0);
  CHECK(wrong["rays"][0]["gradient"]["density"]["r"][2][0].get<double>() == 0.0);  // the tie
  wrong["rays"][0]["gradient"]["density"]["r"][1][0] = 0.0;
  wrong["rays"][0]["gradient"]["density"]["r"][2][0] = tied;
  dir.write("wrong.json", wrong.dump());
  const auto bad = run_cli(dir.path, "gradcheck case.json --candidate wrong.json --rel-tol 1e-6");
  CHECK(bad.status == 1);
  CHECK(bad.err.find("density node 1 position channel r") != std::string::npos);
}

TEST_CASE("gradcheck: null entries in a candidate are not passed, counted and named, exit 1", "[grad][grad_cli]") {
  TempDir dir;
  dir.copy_case("paper-figure-2");
  REQUIRE(run_cli(dir.path, "grad paper-figure-2.json --no-reference -o g.json").status == 0);
  const json report = json::parse(slurp(dir.path / "g.json"));
  // The exact gradient with two entries the "renderer" cannot give: null.
  json cand = json::parse(candidate_from(report, "exact"));
  cand["rays"][1]["gradient"]["color"]["g"][1][1] = nullptr;
  cand["rays"][2]["gradient"]["length"][0][0] = nullptr;
  dir.write("nulls.json", cand.dump());
  const auto r = run_cli(dir.path, "gradcheck paper-figure-2.json --candidate nulls.json --rel-tol 1e-12 --junit j.xml");
  CHECK(r.status == 1);
  const json v = json::parse(r.out);
  CHECK(v["pass"] == false);
  CHECK(v["null_in_candidate"].get<int>() == 2);
  CHECK(v["failed"].get<int>() == 2);  // every other entry is exact's own
  CHECK(v["first_null"]["ray"].get<int>() == 1);
  CHECK(v["first_null"]["block"] == "color");
  CHECK(v["first_null"]["parameter"] == "value");
  CHECK(v["first_null"]["channel"] == "g");
  CHECK(v["first_null"]["got"].is_null());
  CHECK(r.err.find("2 entries null in the candidate (not passed), first: ray 1 color node 1 value channel g") !=
        std::string::npos);
  CHECK(slurp(dir.path / "j.xml").find("entries null in the candidate") != std::string::npos);
  // Only the nulls fail: the closest numeric entry is not called the failure.
  CHECK(r.err.find("every numeric entry passes, closest to its limit: ") != std::string::npos);
  CHECK(r.err.find("worst: ") == std::string::npos);
  // A candidate of nothing but nulls is never a pass.
  json all_null = cand;
  for (json& ray : all_null["rays"]) {
    json& g = ray["gradient"];
    g["background"] = json::array({nullptr, nullptr, nullptr});
    for (const char* block : {"length"})
      for (json& e : g[block]) e = json::array({nullptr, nullptr, nullptr});
    for (json& e : g["scalar"]) e = json::array({json::array({nullptr, nullptr, nullptr}), json::array({nullptr, nullptr, nullptr})});
    for (const char* f : {"density", "color"})
      for (const char* ch : {"r", "g", "b"})
        for (json& node : g[f][ch]) node = json::array({nullptr, nullptr});
  }
  dir.write("all_null.json", all_null.dump());
  const auto n = run_cli(dir.path, "gradcheck paper-figure-2.json --candidate all_null.json");
  CHECK(n.status == 1);
  const json nv = json::parse(n.out);
  CHECK(nv["pass"] == false);
  CHECK(nv["null_in_candidate"] == nv["entries"]);
  CHECK(nv["failed"] == nv["entries"]);
  CHECK(nv["entries"].get<int>() > 0);
}
