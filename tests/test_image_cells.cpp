// A .vti whose field is cell data (one value per voxel, issue 27) read as a mesh of its voxels and
// integrated constant per voxel, against a 50-digit piecewise-constant reference built here from
// VTK's own reading of the file; its arrays listed by `rayint mesh info`, a wrong array name one
// line listing them, exit 2. Fixture written by VTK 9.1: tests/fixtures/vti-direction/.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "test_paths.hpp"
#include "cli_harness.hpp"
#include "rayint/input/vtk_xml_reader.hpp"
#include "rayint/metrics/error_metrics.hpp"
#include "rayint/reference/reference.hpp"

using namespace rayint;
using rayint::test::TempDir;

namespace {

namespace fs = std::filesystem;
const std::string kDir = RAYINT_SOURCE_DIR + "/tests/fixtures/vti-direction/";

nlohmann::json vtk_cells() {
  std::ifstream in(kDir + "probe.json");
  return nlohmann::json::parse(in)["cells"];
}

// The ray origin + t direction through the image's box as segments of constant scalar, one per
// voxel crossed, far -> near: every plane crossing x = origin + i spacing (independently of
// rayint's traversals), each piece's voxel found at its midpoint, its value VTK's cell value.
Ray piecewise_constant_ray(const nlohmann::json& c, const Vec3& o, const Vec3& d) {
  double lo[3], hi[3];
  int n[3];
  for (std::size_t a = 0; a < 3; ++a) {
    const double h = c["spacing"][a].get<double>();
    const double org = c["origin"][a].get<double>();
    lo[a] = org + c["extent"][2 * a].get<double>() * h;
    hi[a] = org + c["extent"][2 * a + 1].get<double>() * h;
    n[a] = c["extent"][2 * a + 1].get<int>() - c["extent"][2 * a].get<int>();
  }
  double t0 = 0.0, t1 = 1e300;
  for (int a = 0; a < 3; ++a) {
    const double ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
    t0 = std::max(t0, std::min(ta, tb));
    t1 = std::min(t1, std::max(ta, tb));
  }
  Ray ray;
  if (!(t1 > t0)) return ray;
  std::vector<double> ts = {t0, t1};
  for (int a = 0; a < 3; ++a)
    for (int i = 1; i < n[a]; ++i) {
      const double t = (lo[a] + i * (hi[a] - lo[a]) / n[a] - o[a]) / d[a];
      if (t > t0 && t < t1) ts.push_back(t);
    }
  std::sort(ts.begin(), ts.end(), std::greater<double>());  // far (large t) first
  for (std::size_t k = 0; k + 1 < ts.size(); ++k) {
    const double tm = 0.5 * (ts[k] + ts[k + 1]);
    int idx[3];
    for (int a = 0; a < 3; ++a)
      idx[a] = std::clamp(static_cast<int>(std::floor((o[a] + tm * d[a] - lo[a]) / (hi[a] - lo[a]) * n[a])), 0, n[a] - 1);
    const double v = c["c"][static_cast<std::size_t>(idx[0] + n[0] * (idx[1] + n[1] * idx[2]))].get<double>();
    ray.segments.push_back({(ts[k] - ts[k + 1]) * d.norm(), v, v});
  }
  return ray;
}

}  // namespace

TEST_CASE("a .vti of cell data is read as its voxels, the cell values VTK reads, in VTK's order",
          "[tfstep][vtkxml][cellmesh]") {
  const nlohmann::json c = vtk_cells();
  const CellMesh m = read_vti_cells(kDir + "cells.vti");
  REQUIRE(m.cell_count() == 60);
  REQUIRE(m.cell_scalars.size() == 60);
  for (std::size_t i = 0; i < 60; ++i) CHECK(m.cell_scalars[i] == c["c"][i].get<double>());
  CHECK(m.points.size() == 6 * 5 * 4);
  // The second cell array by name.
  const CellMesh m2 = read_vti_cells(kDir + "cells.vti", {"c2"});
  CHECK(m2.cell_scalars[7] == 0.5 + 0.01 * 7);
  // The scene's point-grid reader still refuses it, naming the arrays and the way to read it.
  try {
    read_vti(kDir + "cells.vti");
    FAIL("cell data read as a point grid");
  } catch (const std::exception& e) {
    const std::string what = e.what();
    CHECK(what.find(kDir + "cells.vti: ImageData/Piece/CellData: an image with cell data only (\"c\", \"c2\")") == 0);
    CHECK(what.find("--cells split") != std::string::npos);
  }
}

TEST_CASE("CLI: cell data of a .vti integrates constant per voxel, as the 50-digit reference on VTK's values",
          "[tfstep][cellmesh][cli]") {
  TempDir dir;
  const std::string tf = R"("transfer_function": {"density": [[0, 0.3], [1.5, 2.0], [3, 0.5]],
                          "color": {"r": [[0, 1], [3, 0.2]], "g": [[0, 0.1], [2, 1.0]], "b": [[1, 0.4]]}})";
  const std::vector<std::pair<Vec3, Vec3>> rays = {
      {{-1.0, 1.0, 1.6}, {1.0, 0.1, 0.05}},  {{1.5, -1.0, 2.0}, {-0.2, 1.0, 0.3}},
      {{0.2, 1.3, 4.0}, {0.1, -0.05, -1.0}}, {{-1.2, -0.4, 0.2}, {1.0, 1.0, 0.9}},
      {{1.3, 3.0, 1.1}, {-0.3, -1.0, 0.2}}};
  std::string ray_json;
  for (const auto& [o, d] : rays)
    ray_json += std::string(ray_json.empty() ? "" : ", ") + "{\"origin\": [" + std::to_string(o[0]) + ", " +
                std::to_string(o[1]) + ", " + std::to_string(o[2]) + "], \"direction\": [" + std::to_string(d[0]) +
                ", " + std::to_string(d[1]) + ", " + std::to_string(d[2]) + "]}";
  dir.write("cells.json", "{\"name\": \"cells\", " + tf + ", \"mesh_file\": \"" + kDir + "cells.vti\", \"rays\": [" +
                              ray_json + "]}");
  const auto e = test::run_cli(dir.path, "eval cells.json --cells split --methods exact --no-timing");
  INFO(e.err);
  REQUIRE(e.status == 0);
  const nlohmann::json j = nlohmann::json::parse(e.out);
  const nlohmann::json& out_rays = j["cases"][0]["rays"];
  REQUIRE(out_rays.size() == rays.size());
  // The reference: the same transfer function, VTK's cell values, the crossings computed here.
  TransferFunctions t;
  t.density = {PiecewiseLinear{{0, 1.5, 3}, {0.3, 2.0, 0.5}}, PiecewiseLinear{{0, 1.5, 3}, {0.3, 2.0, 0.5}},
               PiecewiseLinear{{0, 1.5, 3}, {0.3, 2.0, 0.5}}};
  t.color = {PiecewiseLinear{{0, 3}, {1, 0.2}}, PiecewiseLinear{{0, 2}, {0.1, 1.0}}, PiecewiseLinear{{1}, {0.4}}};
  const nlohmann::json c = vtk_cells();
  double worst = 0.0;
  std::size_t voxels = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    // The case's numbers as the reader parsed them (the JSON text above, to_string's 6 digits).
    const Vec3 o(std::stod(std::to_string(rays[i].first[0])), std::stod(std::to_string(rays[i].first[1])),
                 std::stod(std::to_string(rays[i].first[2])));
    Vec3 d(std::stod(std::to_string(rays[i].second[0])), std::stod(std::to_string(rays[i].second[1])),
           std::stod(std::to_string(rays[i].second[2])));
    d.normalize();
    const Ray ray = piecewise_constant_ray(c, o, d);
    REQUIRE(!ray.segments.empty());
    voxels += ray.segments.size();
    const ReferenceRay ref = reference_ray(t, ray);
    for (std::size_t ch = 0; ch < 3; ++ch) {
      const double got = out_rays[i]["methods"]["exact"]["intensity"][ch].get<double>();
      INFO("ray " << i << " channel " << ch << " eval " << got << " reference " << ref.intensity[ch].hi);
      // The traversal's crossings and the ones above differ by rounding (~1e-16 of the chord).
      CHECK(relative_error(got, ref.intensity[ch]) < 1e-12);
      worst = std::max(worst, relative_error(got, ref.intensity[ch]));
    }
  }
  CHECK(voxels > 20);  // the rays cross many voxels (one of them a single voxel)
  WARN("[tfstep] cells.vti, 5 rays, " << voxels << " voxels, --cells split exact vs 50-digit piecewise-constant reference: worst rel " << worst);
}

TEST_CASE("CLI: mesh info lists an image's arrays, a wrong array name is one line listing them, exit 2",
          "[tfstep][cellmesh][cli]") {
  TempDir dir;
  const auto info = test::run_cli(dir.path, "mesh info '" + kDir + "cells.vti' --format json");
  INFO(info.err);
  REQUIRE(info.status == 0);
  const nlohmann::json j = nlohmann::json::parse(info.out);
  const std::string dump = j.dump();
  CHECK(dump.find("\"c\"") != std::string::npos);
  CHECK(dump.find("\"c2\"") != std::string::npos);
  const auto pts = test::run_cli(dir.path, "mesh info '" + kDir + "rotated.vti'");
  REQUIRE(pts.status == 0);
  CHECK(pts.out.find("f") != std::string::npos);
  CHECK(pts.out.find("g") != std::string::npos);
  const auto bad = test::run_cli(dir.path, "mesh info '" + kDir + "cells.vti' --array nope");
  CHECK(bad.status == 2);
  CHECK(bad.out.empty());
  CHECK(test::line_count(bad.err) == 1);
  CHECK(bad.err.find("nope") != std::string::npos);
  CHECK(bad.err.find("c2") != std::string::npos);
  // The grid reader (a scene's "grid_file" with "array") likewise.
  try {
    read_vti(kDir + "rotated.vti", "nope");
    FAIL("a missing array was read");
  } catch (const std::exception& x) {
    CHECK(std::string(x.what()) == kDir + "rotated.vti: ImageData/Piece/PointData: no array named \"nope\" (arrays: \"f\", \"g\")");
  }
}
