// The own mode of non-tetrahedral cells (mesh/cell_traversal.hpp) through the CLI: `render
// --shard` + `rayint merge` give the single run's image byte for byte, `render --compare METHOD`
// measures the method on VTK's split against the own interpolation, and zero-volume cells are
// dropped and counted (eval JSON, render --stats, mesh info) or refused with --strict-mesh, and
// `check --candidate` compares a renderer's per-ray intensities with the own interpolation
// (tag [celltraversal][cli]; the check ones also [check]).
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include "test_paths.hpp"
#include "cli_harness.hpp"
#include "bow_tie.hpp"
#include "rayint/input/mesh_case_reader.hpp"
#include "rayint/mesh/cell_mesh.hpp"

using namespace rayint;
using rayint::test::TempDir;
namespace fs = std::filesystem;

namespace {

const std::string kReaders = RAYINT_SOURCE_DIR + "/tests/fixtures/readers/";

std::string bytes_of(const fs::path& p) { return test::slurp(p); }

// A case of the twisted VTK grid (24 hexahedra) seen by a small camera.
std::string twisted_case(const std::string& mesh_file) {
  return R"({"name": "twisted", "transfer_function": {"density": [[0.2, 0.5], [0.45, 4.0], [0.7, 1.0]],
    "color": [[0.2, 1.0], [0.5, 0.1], [0.7, 0.8]]},
    "mesh_file": ")" + mesh_file + R"(",
    "rays": [{"origin": [0.05, 0.02, -1], "direction": [0.1, 0.05, 1]}, {"origin": [-0.3, 0.1, -1], "direction": [0.2, -0.1, 1]}],
    "camera": {"position": [0.4, 0.3, 3.0], "look_at": [0, 0, 0.6], "fov_deg": 40, "width": 10, "height": 7}})";
}

// A legacy VTK file: two hexahedra side by side plus one flat hexahedron (all nodes in z = 0)
// glued to the first one's bottom face: the flat one has zero volume.
std::string hexes_with_flat_cell() {
  return "# vtk DataFile Version 3.0\nflat\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 16 double\n"
         "0 0 0  1 0 0  1 1 0  0 1 0  0 0 1  1 0 1  1 1 1  0 1 1\n"
         "2 0 0  2 1 0  2 0 1  2 1 1\n"
         "0.3 0.2 0  0.7 0.2 0  0.7 0.8 0  0.3 0.8 0\n"
         "CELLS 3 27\n8 0 1 2 3 4 5 6 7\n8 1 8 9 2 5 10 11 6\n8 0 1 2 3 12 13 14 15\n"
         "CELL_TYPES 3\n12\n12\n12\n"
         "POINT_DATA 16\nSCALARS s double 1\nLOOKUP_TABLE default\n"
         "0.1 0.2 0.3 0.4 0.5 0.6 0.7 0.8 0.25 0.35 0.65 0.85 0.2 0.3 0.4 0.5\n";
}

}  // namespace

TEST_CASE("own mode: render --shard and merge give the single run's image byte for byte", "[celltraversal][cli]") {
  TempDir dir;
  dir.write("case.json", twisted_case(kReaders + "cells-twisted.vts"));
  const auto whole = test::run_cli(dir.path, "render case.json -o whole.png --stats whole.json -q");
  REQUIRE(whole.status == 0);
  for (int i = 0; i < 3; ++i) {
    // --stats is an argument of the run (recorded in the shards): the merge writes it.
    const auto s = test::run_cli(dir.path, "render case.json --shard " + std::to_string(i) + "/3 -o part" + std::to_string(i) +
                                               ".json --stats merged.json -q");
    INFO(s.err);
    REQUIRE(s.status == 0);
  }
  const auto merged = test::run_cli(dir.path, "merge part0.json part1.json part2.json -o merged.png");
  INFO(merged.err);
  REQUIRE(merged.status == 0);
  const std::string a = bytes_of(dir.path / "whole.png"), b = bytes_of(dir.path / "merged.png");
  REQUIRE(!a.empty());
  CHECK(a == b);
  const auto sw = nlohmann::json::parse(bytes_of(dir.path / "whole.json"));
  const auto sm = nlohmann::json::parse(bytes_of(dir.path / "merged.json"));
  CHECK(sm["method"] == "own");
  CHECK(sm["cost"]["rays"] == sw["cost"]["rays"]);
  CHECK(sm["cost"]["chords"] == sw["cost"]["chords"]);
  CHECK(sm["failed_pixels"] == 0);
  // A shard of the own mode is refused by a merge with another band missing (one line, exit 2).
  const auto gap = test::run_cli(dir.path, "merge part0.json part2.json -o gap.png");
  CHECK(gap.status == 2);
  CHECK(test::line_count(gap.err) == 1);
  CHECK_FALSE(fs::exists(dir.path / "gap.png"));
}

TEST_CASE("own mode: render --compare measures a method on VTK's split against the own interpolation", "[celltraversal][cli]") {
  TempDir dir;
  dir.write("case.json", twisted_case(kReaders + "cells-twisted.vts"));
  const auto r = test::run_cli(dir.path, "render case.json -o img.png --compare exact --stats s.json");
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(fs::exists(dir.path / "img.error.png"));
  const auto s = nlohmann::json::parse(bytes_of(dir.path / "s.json"));
  REQUIRE(s.contains("compare"));
  CHECK(s["compare"]["method"] == "exact on --cells split");
  CHECK(s["compare"]["pixels"] == 70);
  CHECK(s["compare"]["non_finite"] == 0);
  // The split changes the field of twisted hexahedra (reports/cells/own_vs_split.md: up to ~0.5):
  // the error is far above rounding, and below 1 on this mild transfer function.
  CHECK(s["compare"]["max_rel_error"].get<double>() > 1e-6);
  CHECK(s["compare"]["max_rel_error"].get<double>() < 1.0);
  CHECK(r.err.find("exact on --cells split vs own") != std::string::npos);
  // Shards with --compare merge to the same heat map and image.
  for (int i = 0; i < 2; ++i)
    REQUIRE(test::run_cli(dir.path, "render case.json --compare exact --shard " + std::to_string(i) + "/2 -o c" +
                                        std::to_string(i) + ".json --stats ms.json -q").status == 0);
  const auto m = test::run_cli(dir.path, "merge c0.json c1.json -o merged.png");
  INFO(m.err);
  REQUIRE(m.status == 0);
  CHECK(bytes_of(dir.path / "merged.png") == bytes_of(dir.path / "img.png"));
  CHECK(bytes_of(dir.path / "merged.error.png") == bytes_of(dir.path / "img.error.png"));
  const auto ms = nlohmann::json::parse(bytes_of(dir.path / "ms.json"));
  CHECK(ms["compare"]["max_rel_error"] == s["compare"]["max_rel_error"]);
}

TEST_CASE("own mode: a zero-volume cell is dropped and counted, or refused with --strict-mesh", "[celltraversal][cli]") {
  TempDir dir;
  dir.write("flat.vtk", hexes_with_flat_cell());
  // The library's test: the flat cell has zero volume, the two unit cubes do not.
  const CellMesh m = read_cell_mesh_file((dir.path / "flat.vtk").string());
  REQUIRE(m.cell_count() == 3);
  CHECK_FALSE(zero_volume_cell(m, 0));
  CHECK_FALSE(zero_volume_cell(m, 1));
  CHECK(zero_volume_cell(m, 2));
  dir.write("case.json", R"({"name": "flat", "transfer_function": {"density": [[0, 1], [1, 2]], "color": [[0, 0.5], [1, 1]]},
    "mesh_file": "flat.vtk",
    "rays": [{"origin": [0.5, 0.5, -1], "direction": [0, 0, 1]}, {"origin": [1.5, 0.5, -1], "direction": [0, 0, 1]}],
    "camera": {"position": [1, 0.5, 4], "look_at": [1, 0.5, 0.5], "fov_deg": 30, "width": 6, "height": 4}})");
  // eval: counted in the JSON; the rays still converge (the flat cell covers no volume).
  const auto e = test::run_cli(dir.path, "eval case.json -q");
  INFO(e.err);
  REQUIRE(e.status == 0);
  const auto je = nlohmann::json::parse(e.out);
  CHECK(je["cases"][0]["mesh_repairs"]["dropped_zero_volume"] == 1);
  CHECK(je["cases"][0]["mesh_repairs"]["dropped_zero_volume_by_type"]["hexahedron"] == 1);
  CHECK(je["cases"][0]["cells"]["hexahedron"] == 2);
  CHECK(je["cases"][0]["failed"] == 0);
  CHECK(je["cases"][0]["max_abs_error"].get<double>() <= 1e-13);  // against the 50-digit cell reference
  // render --stats and stderr.
  const auto r = test::run_cli(dir.path, "render case.json -o img.png --stats s.json");
  REQUIRE(r.status == 0);
  CHECK(r.err.find("1 zero-volume cells dropped") != std::string::npos);
  const auto s = nlohmann::json::parse(bytes_of(dir.path / "s.json"));
  CHECK(s["mesh"]["repairs"]["dropped_zero_volume"] == 1);
  // mesh info.
  const auto info = test::run_cli(dir.path, "mesh info flat.vtk --format json");
  REQUIRE(info.status == 0);
  const auto ji = nlohmann::json::parse(info.out);
  CHECK(ji["zero_volume_cells"]["total"] == 1);
  CHECK(ji["zero_volume_cells"]["by_type"]["hexahedron"] == 1);
  const auto text = test::run_cli(dir.path, "mesh info flat.vtk");
  CHECK(text.out.find("zero volume: 1 (hexahedron 1; dropped in the own mode)") != std::string::npos);
  // --strict-mesh: refused naming the cell, exit 2, nothing written.
  const auto before = dir.entries();
  const auto strict = test::run_cli(dir.path, "eval case.json --strict-mesh -o strict.json");
  CHECK(strict.status == 2);
  CHECK(test::line_count(strict.err) == 1);
  CHECK(strict.err.find("cells[2]: a hexahedron of zero volume") != std::string::npos);
  CHECK(dir.entries() == before);
}

namespace {

// A candidate file for `rayint check` of case `name` with one [r, g, b] per ray.
std::string candidate_of(const std::string& name, const std::vector<std::array<double, 3>>& rays) {
  nlohmann::json j = {{"case", name}, {"renderer", "test"}, {"rays", nlohmann::json::array()}};
  for (const auto& v : rays) j["rays"].push_back({{"intensity", {v[0], v[1], v[2]}}});
  return j.dump(1);
}

// The per-ray 50-digit reference column of `rayint eval`'s own-mode JSON: independent of the
// double path check_candidate_own takes its expected values from (reference/cell_reference.hpp).
std::vector<std::array<double, 3>> eval_reference_column(const fs::path& dir, const std::string& case_file) {
  const auto e = test::run_cli(dir, "eval " + case_file + " -q");
  INFO(e.err);
  REQUIRE(e.status == 0);
  const auto j = nlohmann::json::parse(e.out);
  REQUIRE(j["mode"] == "own");
  std::vector<std::array<double, 3>> out;
  for (const auto& r : j["cases"][0]["rays"]) {
    REQUIRE(r["reference"].is_array());
    out.push_back({r["reference"][0].get<double>(), r["reference"][1].get<double>(), r["reference"][2].get<double>()});
  }
  return out;
}

// A case of the gmsh wedge mesh (tests/fixtures/readers/cells-prism.geo: a square prism of
// wedges, z in [0, 0.65]) seen by a 6 x 5 camera from above.
std::string prism_case(const std::string& mesh_file) {
  return R"({"name": "prism", "transfer_function": {"density": [[0, 0.5], [0.5, 3.0], [1, 1.0]],
    "color": [[0, 1.0], [0.5, 0.2], [1, 0.7]]},
    "mesh_file": ")" + mesh_file + R"(", "background": [0.1, 0.2, 0.3],
    "camera": {"position": [0.2, 0.1, 3.0], "look_at": [0, 0, 0.3], "fov_deg": 40, "width": 6, "height": 5}})";
}

}  // namespace

TEST_CASE("own mode: check --candidate passes the 50-digit reference's intensities and names a spoiled ray", "[celltraversal][cli][check]") {
  TempDir dir;
  struct Mesh {
    const char* case_name;
    std::string json;
  };
  for (const Mesh& m : {Mesh{"twisted", twisted_case(kReaders + "cells-twisted.vts")},
                        Mesh{"prism", prism_case(kReaders + "cells-prism-41.msh")}}) {
    INFO(m.case_name);
    dir.write("case.json", m.json);
    const std::vector<std::array<double, 3>> ref = eval_reference_column(dir.path, "case.json");
    REQUIRE(ref.size() >= 2);
    // The rays see the volume: not every intensity is the background (or 0).
    const auto bg = nlohmann::json::parse(m.json).value("background", std::vector<double>{0, 0, 0});
    long seen = 0;
    for (const auto& v : ref) seen += std::fabs(v[0] - bg[0]) > 1e-3 ? 1 : 0;
    CHECK(seen > 0);

    // (1) The reference's intensities pass at the default tolerance (rel 1e-6), exit 0.
    dir.write("cand.json", candidate_of(m.case_name, ref));
    const auto pass = test::run_cli(dir.path, "check case.json --candidate cand.json -o pass.json --junit pass.xml");
    INFO(pass.err);
    CHECK(pass.status == 0);
    CHECK(pass.err.find("mode own") != std::string::npos);
    CHECK(pass.err.find("PASS") != std::string::npos);
    const auto pj = nlohmann::json::parse(bytes_of(dir.path / "pass.json"));
    CHECK(pj["pass"] == true);
    CHECK(pj["expected"] == "own");
    CHECK(pj["summary"]["rays"].get<std::size_t>() == ref.size());
    CHECK(pj["summary"]["expected_failed_rays"] == 0);
    CHECK(pj["summary"]["reference_failed_rays"] == 0);
    // The expected values (the double path) agree with the reference they are checked against.
    CHECK(pj["summary"]["expected_max_rel_uncertainty"].get<double>() < 1e-10);
    CHECK(bytes_of(dir.path / "pass.xml").find("failures=\"0\"") != std::string::npos);

    // (2) One ray spoiled by 1e-3: exit 1, that ray named as the worst, the only one failing.
    const std::size_t bad = ref.size() / 2;
    std::vector<std::array<double, 3>> spoiled = ref;
    spoiled[bad][1] += 1e-3;
    dir.write("spoiled.json", candidate_of(m.case_name, spoiled));
    const auto fail = test::run_cli(dir.path, "check case.json --candidate spoiled.json -o fail.json --junit fail.xml");
    INFO(fail.err);
    CHECK(fail.status == 1);
    CHECK(fail.err.find("FAIL") != std::string::npos);
    CHECK(fail.err.find("worst: ray " + std::to_string(bad) + " channel g") != std::string::npos);
    const auto fj = nlohmann::json::parse(bytes_of(dir.path / "fail.json"));
    CHECK(fj["pass"] == false);
    CHECK(fj["summary"]["failed_rays"] == 1);
    CHECK(fj["summary"]["worst"]["ray"].get<std::size_t>() == bad);
    CHECK(fj["rays"][bad]["pass"] == false);
    CHECK(fj["rays"][bad]["channels"][1]["abs_error"].get<double>() == Approx(1e-3).epsilon(1e-6));
    CHECK(bytes_of(dir.path / "fail.xml").find("ray[" + std::to_string(bad) + "] channel g") != std::string::npos);

    // (3) One ray too few: bad input, one line naming the candidate file and its field, exit 2.
    std::vector<std::array<double, 3>> short_ref(ref.begin(), ref.end() - 1);
    dir.write("short.json", candidate_of(m.case_name, short_ref));
    const auto bad_input = test::run_cli(dir.path, "check case.json --candidate short.json -o short-diff.json");
    test::check_one_line_exit(bad_input);
    CHECK(bad_input.err.find("short.json: rays: has " + std::to_string(ref.size() - 1) + " entries but the case file") !=
          std::string::npos);
    CHECK_FALSE(fs::exists(dir.path / "short-diff.json"));
  }
}

TEST_CASE("own mode: check --candidate fails rays whose own integration did not converge", "[celltraversal][cli][check]") {
  TempDir dir;
  // The bow-tie hexahedron of [celltraversal] (top face nodes 6 and 7 swapped): Newton cannot
  // locate points in it, so some rays have no expected value. Whatever the candidate says there,
  // the check fails (exit 1), those rays marked with why, their errors null, never 0.
  const nlohmann::json ej = test::eval_bow_tie(dir, 12);
  const long failed = ej["cases"][0]["failed"].get<long>();
  // The candidate: eval's values where it converged, 0 where it did not (what a renderer that
  // drew nothing there would give).
  std::vector<std::array<double, 3>> cand;
  for (const auto& r : ej["cases"][0]["rays"])
    cand.push_back(r["intensity"].is_null() ? std::array<double, 3>{0, 0, 0}
                                            : std::array<double, 3>{r["intensity"][0].get<double>(), r["intensity"][1].get<double>(),
                                                                    r["intensity"][2].get<double>()});
  dir.write("cand.json", candidate_of("bow", cand));
  const auto c = test::run_cli(dir.path, "check bow.json --candidate cand.json --no-reference -o diff.json -q --junit j.xml");
  CHECK(c.status == 1);
  const auto d = nlohmann::json::parse(bytes_of(dir.path / "diff.json"));
  CHECK(d["pass"] == false);
  CHECK(d["summary"]["expected_failed_rays"].get<long>() == failed);
  CHECK(d["summary"]["failed_rays"].get<long>() == failed);
  long marked = 0;
  for (std::size_t i = 0; i < d["rays"].size(); ++i) {
    const auto& r = d["rays"][i];
    const bool no_value = ej["cases"][0]["rays"][i]["intensity"].is_null();
    CHECK(r["pass"] == !no_value);
    if (!no_value) continue;
    ++marked;
    CHECK_FALSE(r["expected_failure"].get<std::string>().empty());
    for (const auto& ch : r["channels"]) {
      CHECK(ch["expected"].is_null());
      CHECK(ch["abs_error"].is_null());
      CHECK(ch["pass"] == false);
    }
  }
  CHECK(marked == failed);
  CHECK(bytes_of(dir.path / "j.xml").find("no expected value: ") != std::string::npos);
}

// ---- rayint bench on cells other than tetrahedra: own interpolation against VTK's split ----

namespace {

// The largest |I_split - I_own| and |I_split - I_own| / |I_own| (absolute where I_own = 0) over
// the rays and channels of two eval runs of one case: the own mode (cases[0].rays[i].intensity)
// and --cells split --methods exact.
std::array<double, 2> max_eval_difference(const nlohmann::json& own, const nlohmann::json& split) {
  const auto& a = own["cases"][0]["rays"];
  const auto& b = split["cases"][0]["rays"];
  REQUIRE(a.size() == b.size());
  std::array<double, 2> worst{0.0, 0.0};
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t c = 0; c < 3; ++c) {
      const double io = a[i]["intensity"][c].get<double>();
      const double d = std::fabs(b[i]["methods"]["exact"]["intensity"][c].get<double>() - io);
      worst[0] = std::max(worst[0], d);
      worst[1] = std::max(worst[1], io != 0.0 ? d / std::fabs(io) : d);
    }
  return worst;
}

const std::string kMixedCase = R"({"name": "mixed", "transfer_function": {"density": [[0, 0.5], [0.5, 3.0], [1, 1.0]],
    "color": [[0, 1.0], [0.5, 0.1], [1, 0.8]]},
    "mesh_file": ")" + kReaders + R"(cells-mixed-41.msh",
    "camera": {"position": [1.2, 0.4, 4.0], "look_at": [1, 0.5, 0.5], "fov_deg": 35, "width": 12, "height": 8}})";

}  // namespace

TEST_CASE("own mode: bench times the own interpolation against VTK's split and states the difference", "[celltraversal][cli][bench]") {
  TempDir dir;
  dir.write("twisted.json", twisted_case(kReaders + "cells-twisted.vts"));
  dir.write("mixed.json", kMixedCase);
  const auto r = test::run_cli(dir.path, "bench twisted.json mixed.json --batches 3 -o b.json");
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.out.find("own/split") != std::string::npos);
  CHECK(r.out.find("failed:") == std::string::npos);
  const auto b = nlohmann::json::parse(bytes_of(dir.path / "b.json"));
  CHECK(b["report"] == "bench");
  CHECK(b["methods"].empty());  // nothing to sweep: no segment case
  const auto& o = b["own_vs_split"];
  CHECK(o["repetitions"] == 3);
  CHECK(o["threads"] == 1);
  CHECK(o["clock"] == "thread CPU time");
  REQUIRE(o["cases"].size() == 2);
  for (const char* name : {"twisted", "mixed"}) {
    const std::size_t k = std::string(name) == "twisted" ? 0 : 1;
    const auto& c = o["cases"][k];
    INFO(name << ": " << c.dump());
    CHECK(c["name"] == name);
    // What eval says of the same case, in both modes: the ray count, the cells, the tetrahedra of
    // the split, and the difference of the two answers ray by ray.
    const auto own = test::run_cli(dir.path, std::string("eval ") + name + ".json -q --no-reference");
    const auto split = test::run_cli(dir.path, std::string("eval ") + name + ".json --cells split --methods exact -q --no-reference");
    REQUIRE(own.status == 0);
    REQUIRE(split.status == 0);
    const auto jo = nlohmann::json::parse(own.out), js = nlohmann::json::parse(split.out);
    CHECK(c["rays"] == jo["cases"][0]["rays"].size());
    CHECK(c["compared_rays"] == c["rays"]);
    CHECK(c["cells"] == jo["cases"][0]["cells"]);
    CHECK(c["tets"] == js["cases"][0]["mesh_repairs"]["tets_read"]);
    CHECK(c["complete"] == true);
    CHECK(c["own_failed_rays"] == 0);
    CHECK(c["split_failed_rays"] == 0);
    const double own_s = c["own_seconds"].get<double>(), split_s = c["split_seconds"].get<double>();
    CHECK(own_s > 0);
    CHECK(split_s > 0);
    CHECK(c["own_over_split"].get<double>() == Approx(own_s / split_s).epsilon(1e-12));
    CHECK(c["own_seconds_per_ray"].get<double>() == Approx(own_s / c["rays"].get<double>()).epsilon(1e-12));
    // The same integrations as eval's (single-threaded, same code): the difference is eval's to rounding.
    const std::array<double, 2> diff = max_eval_difference(jo, js);
    CHECK(diff[0] > 1e-6);  // the split changes the field of these cells (reports/cells/own_vs_split.md)
    CHECK(c["max_abs_difference"].get<double>() == Approx(diff[0]).epsilon(1e-9));
    CHECK(c["max_rel_difference"].get<double>() == Approx(diff[1]).epsilon(1e-9));
  }
  CHECK(o["cases"][1]["cells"]["pyramid"] == 4);
  CHECK(o["cases"][0]["structured_split"] == true);
  CHECK(o["cases"][1]["structured_split"] == false);
}

TEST_CASE("own mode: bench counts rays whose own integration failed and gives no ratio", "[celltraversal][cli][bench]") {
  TempDir dir;
  const nlohmann::json ej = test::eval_bow_tie(dir, 12);
  const long failed = ej["cases"][0]["failed"].get<long>();
  const auto r = test::run_cli(dir.path, "bench bow.json --batches 1 -o b.json");
  INFO(r.err);
  REQUIRE(r.status == 0);  // bench's rule: the report was written, failures counted in it
  CHECK(r.out.find("failed: bow: own on " + std::to_string(failed) + " of 144 rays") != std::string::npos);
  const auto c = nlohmann::json::parse(bytes_of(dir.path / "b.json"))["own_vs_split"]["cases"][0];
  INFO(c.dump());
  CHECK(c["own_failed_rays"] == failed);
  CHECK(c["complete"] == false);
  CHECK(c["own_over_split"].is_null());
  CHECK_FALSE(c["own_failure"].get<std::string>().empty());
  // The bow tie's split overlaps itself: TetTraversal refuses it, so there is no split at all
  // -- no split time, no difference, said why -- rather than numbers from half a comparison.
  CHECK(c["split_ran"] == false);
  CHECK(c["split_seconds"].is_null());
  CHECK(c["tets"].is_null());
  CHECK(c["compared_rays"] == 0);
  CHECK(c["max_abs_difference"].is_null());
  CHECK(c["max_rel_difference"].is_null());
  CHECK(c["split_failure"].get<std::string>().find("overlaps") != std::string::npos);
  CHECK(r.out.find("failed: bow: no split: ") != std::string::npos);
}

TEST_CASE("own mode: bench with segment cases keeps the sweep and adds own_vs_split, refuses --shard", "[celltraversal][cli][bench]") {
  TempDir dir;
  dir.write("twisted.json", twisted_case(kReaders + "cells-twisted.vts"));
  const auto r = test::run_cli(dir.path, "bench twisted.json " + RAYINT_SOURCE_DIR +
                                             "/cases/constant-scalar-segments.json --methods riemann --batches 1 --batch-seconds 1e-5 -q -o b.json");
  INFO(r.err);
  REQUIRE(r.status == 0);
  const auto b = nlohmann::json::parse(bytes_of(dir.path / "b.json"));
  REQUIRE(b["cases"].size() == 1);
  CHECK(b["methods"].size() == 2);  // exact and riemann, as without the mesh case
  REQUIRE(b["own_vs_split"]["cases"].size() == 1);
  CHECK(b["own_vs_split"]["cases"][0]["complete"] == true);
  CHECK(r.out.find("own vs split") != std::string::npos);
  const auto s = test::run_cli(dir.path, "bench twisted.json --shard 0/2 -o part.json");
  CHECK(s.status == 2);
  CHECK(s.err.rfind("rayint: error: twisted.json: mesh_file: cells other than tetrahedra", 0) == 0);
}
