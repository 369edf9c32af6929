// ParaView 5.11's built-in colour maps as shipped (issue 27): every preset of
// vtkSMTransferFunctionPresets, exported by ParaView's own pvpython, imported with a plain
// `rayint tf import FILE --name NAME`, and compared with the colours ParaView's lookup table
// (VTK 9.2's vtkColorTransferFunction, the preset applied as ParaView applies it) gives at ~600
// scalars a preset. Fixtures and the script that wrote them: tests/data/tf/paraview-5.11-*,
// scripts/paraview-presets.py (do not edit; ParaView is not needed to run these tests).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "test_paths.hpp"
#include "cli_harness.hpp"
#include "rayint/core/error.hpp"
#include "rayint/input/case_reader.hpp"
#include "rayint/input/paraview_preset.hpp"
#include "rayint/integrators/integrator.hpp"
#include "rayint/metrics/error_metrics.hpp"
#include "rayint/reference/reference.hpp"
#include "tolerances.hpp"

namespace {

namespace fs = std::filesystem;
const fs::path kData = fs::path(RAYINT_SOURCE_DIR) / "tests" / "data" / "tf";

// A float64 .npy of shape (rows, columns), C order: the oracle's layout
// (scripts/paraview-presets.py).
struct Table {
  std::size_t rows = 0, columns = 0;
  std::vector<double> v;
  double at(std::size_t r, std::size_t c) const { return v[r * columns + c]; }
};

Table read_npy(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  REQUIRE(bytes.size() > 10);
  REQUIRE(bytes.compare(0, 6, "\x93NUMPY") == 0);
  REQUIRE(bytes[6] == 1);  // version 1.0: 2-byte header length
  const std::size_t header_len =
      static_cast<unsigned char>(bytes[8]) |
      (static_cast<std::size_t>(static_cast<unsigned char>(bytes[9])) << 8);
  const std::string header = bytes.substr(10, header_len);
  REQUIRE(header.find("'descr': '<f8'") != std::string::npos);
  REQUIRE(header.find("'fortran_order': False") != std::string::npos);
  const std::size_t open = header.find("'shape': (");
  REQUIRE(open != std::string::npos);
  Table t;
  std::istringstream shape(header.substr(open + 10));
  char comma = 0;
  shape >> t.rows >> comma >> t.columns;
  REQUIRE(comma == ',');
  const std::size_t offset = 10 + header_len;
  REQUIRE(bytes.size() == offset + t.rows * t.columns * sizeof(double));
  t.v.resize(t.rows * t.columns);
  std::memcpy(t.v.data(), bytes.data() + offset, t.v.size() * sizeof(double));
  return t;
}

nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

rayint::PresetImportRequest request(const std::string& file, const std::string& name,
                                    std::size_t index, double tolerance) {
  rayint::PresetImportRequest r;
  r.file = (kData / file).string();
  r.name = name;
  r.index = index;
  r.options.tolerance = tolerance;
  r.request_source = "test";
  return r;
}

struct Deviation {
  double color = 0.0, curve = 0.0, opacity = 0.0;
  std::size_t samples = 0;
};

// The imported functions and rayint's VTK curves against the oracle rows of one preset. Rows
// whose oracle colour is NaN (VTK's log scale below 0) are skipped.
Deviation compare(const rayint::PresetImport& imp, const Table& oracle, std::size_t first,
                  std::size_t count) {
  Deviation d;
  const rayint::TransferFunctions& tf = imp.result.transfer;
  for (std::size_t i = first; i < first + count; ++i) {
    const double x = oracle.at(i, 0);
    if (std::isnan(oracle.at(i, 1))) continue;
    ++d.samples;
    const rayint::Rgb curve = imp.preset.color(x);
    for (int j = 0; j < 3; ++j) {
      const double vtk = oracle.at(i, 1 + static_cast<std::size_t>(j));
      d.color = std::max(d.color, std::fabs(tf.color[static_cast<std::size_t>(j)](x) - vtk));
      d.curve = std::max(d.curve, std::fabs(curve[static_cast<std::size_t>(j)] - vtk));
    }
    if (oracle.columns > 4)
      d.opacity = std::max(d.opacity, std::fabs(tf.density[0](x) - oracle.at(i, 4)));
  }
  return d;
}

}  // namespace

TEST_CASE(
    "ParaView 5.11 built-in presets: every continuous one imports as shipped, within the tolerance "
    "of VTK's colours",
    "[tf][paraview]") {
  const nlohmann::json presets = read_json(kData / "paraview-5.11-presets.json");
  const nlohmann::json meta = read_json(kData / "paraview-5.11-oracle.json");
  const Table oracle = read_npy(kData / meta["built_in"]["file"].get<std::string>());
  REQUIRE(presets.size() == 195);
  std::map<std::string, const nlohmann::json*> oracle_of;  // by index
  for (const auto& e : meta["built_in"]["presets"])
    oracle_of[std::to_string(e["preset_index"].get<int>())] = &e;

  for (const double tolerance : {1e-6, 1e-4}) {
    std::map<std::string, int> continuous, imported;
    int categorical = 0, refused_right = 0;
    double worst_color = 0.0, worst_curve = 0.0, worst_reported = 0.0;
    std::string worst_name;
    std::size_t samples = 0;
    for (std::size_t i = 0; i < presets.size(); ++i) {
      const nlohmann::json& p = presets[i];
      const std::string name = p["Name"].get<std::string>();
      INFO(name << " [" << i << "], tolerance " << tolerance);
      rayint::PresetImportRequest r = request("paraview-5.11-presets.json", name, i, tolerance);
      if (p.contains("IndexedColors")) {
        ++categorical;
        try {
          rayint::import_paraview_preset(r);
          FAIL("a categorical preset imported");
        } catch (const rayint::InputError& e) {
          const std::string what = e.what();
          const bool right =
              what.find("[" + std::to_string(i) + "].IndexedColors: a categorical colour map") !=
                  std::string::npos &&
              what.find("categorical maps have no continuous transfer function") !=
                  std::string::npos;
          CHECK(right);
          refused_right += right;
        }
        continue;
      }
      const std::string space = p["ColorSpace"].get<std::string>();
      ++continuous[space];
      const rayint::PresetImport imp = rayint::import_paraview_preset(r);
      CHECK(imp.default_opacity);  // none of the built-ins has opacity Points
      CHECK(imp.result.color.converged);
      CHECK(imp.result.color.max_deviation <= tolerance);
      const nlohmann::json& e = *oracle_of.at(std::to_string(i));
      // The colour space the lookup table ended with is the one rayint evaluates.
      const std::string applied = e["applied"]["ColorSpace"].get<std::string>();
      CHECK(applied == (space == "CIELAB" ? "RGB" : space));
      const Deviation d =
          compare(imp, oracle, e["rows"][0].get<std::size_t>(), e["rows"][1].get<std::size_t>());
      CHECK(d.curve <= 1e-12);      // rayint's VTK curves vs VTK 9.2: rounding
      CHECK(d.color <= tolerance);  // the linearised colour vs VTK: the stated tolerance holds
      // The default opacity: ParaView's ramp 0 -> 1 over the colour range.
      const double x0 = imp.preset.color.nodes.front().x, x1 = imp.preset.color.nodes.back().x;
      CHECK(imp.result.transfer.density[0](x0) == 0.0);
      CHECK(imp.result.transfer.density[0](x1) == 1.0);
      CHECK(std::fabs(imp.result.transfer.density[0](0.5 * (x0 + x1)) - 0.5) <= 1e-15);
      if (d.curve <= 1e-12 && d.color <= tolerance) ++imported[space];
      samples += d.samples;
      worst_curve = std::max(worst_curve, d.curve);
      worst_reported = std::max(worst_reported, imp.result.color.max_deviation);
      if (d.color > worst_color) {
        worst_color = d.color;
        worst_name = name;
      }
    }
    int total_continuous = 0, total_imported = 0;
    std::string by_space;
    for (const auto& [space, n] : continuous) {
      total_continuous += n;
      total_imported += imported[space];
      by_space += " " + space + " " + std::to_string(imported[space]) + "/" + std::to_string(n);
    }
    CHECK(total_continuous == 128);
    CHECK(total_imported == 128);
    CHECK(categorical == 67);
    CHECK(refused_right == 67);
    WARN("ParaView 5.11 built-ins, tolerance "
         << tolerance << ": imported within tolerance " << total_imported << "/" << total_continuous
         << " continuous (" << by_space << "); categorical refused with the message "
         << refused_right << "/" << categorical << "; worst |colour - VTK| " << worst_color << " ("
         << worst_name << ") over " << samples << " samples; worst reported max deviation "
         << worst_reported << "; rayint's VTK curves vs VTK 9.2 " << worst_curve);
  }
}

TEST_CASE(
    "ParaView 5.11 built-in presets: the linearised colour is within the tolerance between its "
    "nodes too",
    "[tf][paraview]") {
  // The oracle's scalars are not where a chord deviates most. Between every two nodes of the
  // imported colour, 24 points offset from the importer's probes ((k + 1/2)/24 of the piece, the
  // probes sit at k/17) compare the chord with rayint's VTK curves, which equal VTK 9.2 bit for bit
  // at all 75,768 oracle scalars (previous test). With the 16 probes alone and no maximisation,
  // 23 presets exceeded 1e-6 between probes (issue 27).
  const nlohmann::json presets = read_json(kData / "paraview-5.11-presets.json");
  constexpr double tolerance = 1e-6;
  double worst = 0.0;
  std::string worst_name;
  int over = 0;
  for (std::size_t i = 0; i < presets.size(); ++i) {
    if (presets[i].contains("IndexedColors")) continue;
    const std::string name = presets[i]["Name"].get<std::string>();
    INFO(name);
    const rayint::PresetImport imp =
        rayint::import_paraview_preset(request("paraview-5.11-presets.json", name, i, tolerance));
    const auto& color = imp.result.transfer.color;
    double preset_worst = 0.0;
    for (std::size_t k = 0; k + 1 < color[0].scalar.size(); ++k) {
      const double a = color[0].scalar[k], b = color[0].scalar[k + 1];
      for (int q = 0; q < 24; ++q) {
        const double x = a + (b - a) * (q + 0.5) / 24;
        if (!(x > a && x < b)) continue;
        const rayint::Rgb vtk = imp.preset.color(x);
        for (std::size_t j = 0; j < 3; ++j)
          preset_worst = std::max(preset_worst, std::fabs(color[j](x) - vtk[j]));
      }
    }
    CHECK(preset_worst <= tolerance);
    over += preset_worst > tolerance;
    if (preset_worst > worst) {
      worst = preset_worst;
      worst_name = name;
    }
  }
  WARN("between the imported nodes (24 points a piece), worst |colour - VTK curve| "
       << worst << " (" << worst_name << "); presets over 1e-6: " << over);
}

TEST_CASE(
    "presets exported by ParaView with opacity Points and UseLogScale import as ParaView draws "
    "them",
    "[tf][paraview]") {
  // paraview-5.11-exported.json: ParaView's ExportTransferFunction of Viridis on its own range with
  // the default opacity, and of Viridis and Cool to Warm rescaled to [0.1, 1000] on a log scale.
  // ParaView's colour is log-scaled there; its opacity function is not (measured: the fifth
  // column).
  const nlohmann::json meta = read_json(kData / "paraview-5.11-oracle.json");
  const Table oracle = read_npy(kData / meta["exported"]["file"].get<std::string>());
  REQUIRE(meta["exported"]["presets"].size() == 3);
  for (const auto& e : meta["exported"]["presets"]) {
    const std::string name = e["name"].get<std::string>();
    INFO(name);
    const rayint::PresetImport imp = rayint::import_paraview_preset(
        request("paraview-5.11-exported.json", name, e["preset_index"].get<std::size_t>(), 1e-6));
    CHECK_FALSE(imp.default_opacity);
    CHECK(imp.preset.color.log_scale == (e["applied"]["UseLogScale"].get<int>() == 1));
    CHECK(e["applied"]["OpacityUseLogScale"].get<int>() == 0);
    const Deviation d =
        compare(imp, oracle, e["rows"][0].get<std::size_t>(), e["rows"][1].get<std::size_t>());
    CHECK(d.samples + (imp.preset.color.log_scale ? 2u : 0u) >=
          e["rows"][1].get<std::size_t>());  // NaN: x < 0 only
    CHECK(d.curve <= 1e-12);
    CHECK(d.color <= 1e-6);
    CHECK(d.opacity <= 1e-15);  // the ramp's two nodes are exact
    CHECK(imp.result.color.max_deviation <= 1e-6);
    WARN(name << ": |colour - VTK| " << d.color << ", |opacity - VTK| " << d.opacity << " over "
              << d.samples << " samples; colour " << imp.result.color.nodes << " nodes");
  }
}

TEST_CASE(
    "ParaView presets: a name two presets share is refused listing both, and --index picks one",
    "[tf][paraview][cli]") {
  using rayint::test::run_cli;
  rayint::test::TempDir dir;
  fs::copy_file(kData / "paraview-5.11-presets.json", dir.path / "maps.json");
  const nlohmann::json presets = read_json(kData / "paraview-5.11-presets.json");
  std::vector<std::size_t> blues;
  for (std::size_t i = 0; i < presets.size(); ++i)
    if (presets[i]["Name"] == "Blues") blues.push_back(i);
  REQUIRE(blues.size() == 2);
  const std::set<std::string> inputs = dir.entries();
  const auto r = run_cli(dir.path, "tf import maps.json --name Blues -o out.json");
  rayint::test::check_usage_error(r);
  // ParaView 5.11 ships a continuous (Lab) and a categorical "Blues".
  REQUIRE(presets[blues[0]]["ColorSpace"] == "Lab");
  REQUIRE(presets[blues[1]].contains("IndexedColors"));
  const std::string listed = "2 presets are named \"Blues\": [" + std::to_string(blues[0]) +
                             "] (Lab), [" + std::to_string(blues[1]) +
                             "] (categorical); choose one by its index (--index)";
  CHECK(r.err.find("maps.json: (root): " + listed) != std::string::npos);
  CHECK(dir.entries() == inputs);

  const auto ok = run_cli(dir.path, "tf import maps.json --name Blues --index " +
                                        std::to_string(blues[0]) + " -o out.json");
  REQUIRE(ok.status == 0);
  const auto cat =
      run_cli(dir.path, "tf import maps.json --name Blues --index " + std::to_string(blues[1]));
  rayint::test::check_usage_error(cat);
  CHECK(cat.err.find("maps.json: [" + std::to_string(blues[1]) +
                     "].IndexedColors: a categorical colour map") != std::string::npos);
  CHECK(ok.err.find("note: the preset has no opacity Points: the opacity is ParaView's default") !=
        std::string::npos);
  const auto wrong =
      run_cli(dir.path, "tf import maps.json --name Viridis --index " + std::to_string(blues[1]));
  rayint::test::check_usage_error(wrong);
  CHECK(wrong.err.find("].Name: the preset is \"Blues\", not \"Viridis\"") != std::string::npos);
  // The same in a case file: "index" picks one.
  const std::string rays = R"j("rays": [{"segments": [{"length": 1, "scalar": [0, 1]}]}])j";
  dir.write(
      "shared.json",
      R"j({"name": "c", "transfer_function": {"paraview_preset": "maps.json", "name": "Blues"}, )j" +
          rays + "}");
  CHECK_THROWS_WITH(
      rayint::read_case_file((dir.path / "shared.json").string()),
      Catch::Contains("maps.json: (root): " + listed.substr(0, listed.find("(--index)")) +
                      "(transfer_function.index)"));
  dir.write(
      "picked.json",
      R"j({"name": "c", "transfer_function": {"paraview_preset": "maps.json", "name": "Blues", "index": )j" +
          std::to_string(blues[0]) + "}, " + rays + "}");
  const rayint::Case picked = rayint::read_case_file((dir.path / "picked.json").string());
  const rayint::PresetImport direct = rayint::import_paraview_preset(
      request("paraview-5.11-presets.json", "Blues", blues[0], 1e-6));
  CHECK(picked.transfer.color[1].value == direct.result.transfer.color[1].value);
  CHECK(picked.transfer.density[0].value == direct.result.transfer.density[0].value);
  const auto beyond = run_cli(dir.path, "tf import maps.json --index 195");
  rayint::test::check_usage_error(beyond);
  CHECK(beyond.err.find("rayint tf import: --index: no preset [195]: ") != std::string::npos);
}

TEST_CASE(
    "transfer functions with jumps: exact matches the 50-digit reference, the sampling methods "
    "converge",
    "[tf][paraview][methods]") {
  // Two cases in tests/data/tf/: ParaView's "Spectrum Step" as shipped (kappa jumps at 7 scalars,
  // default opacity ramp) and jumps.json (kappa jumps at a repeated RGBPoints scalar, rho at a
  // sharpness-1 opacity step). The import makes each a true jump at VTK's switch (a repeated
  // scalar: docs/transfer-function-conventions.md), which every method sees as a breakpoint
  // whose pieces take the value on their own side. Rays cross the jumps both ways, end on them,
  // and hold a constant scalar exactly on one.
  using rayint::test::MethodTolerances;
  using rayint::test::Tolerances;
  struct JumpCase {
    const char* file;
    std::vector<std::size_t> constant_on_jump;  // rays with a segment of constant scalar at a jump
  };
  for (const JumpCase& jc :
       {JumpCase{"case-spectrum-step.json", {2}}, JumpCase{"case-jumps.json", {1, 2}}}) {
    const rayint::Case c = rayint::read_case_file((kData / jc.file).string());
    INFO(jc.file);
    std::vector<rayint::ReferenceRay> ref;
    for (const rayint::Ray& ray : c.rays) ref.push_back(rayint::reference_ray(c.transfer, ray));
    // Per ray, the largest relative error over channels (intensity and transmittance).
    auto errors = [&](const std::string& spec) {
      const auto m = rayint::make_integrator(rayint::parse_method_spec(spec), c.transfer);
      std::vector<double> out;
      for (std::size_t i = 0; i < c.rays.size(); ++i) {
        const rayint::RayResult r = m->integrate(c.rays[i], nullptr);
        double e = 0.0;
        for (int k = 0; k < rayint::kChannels; ++k)
          e = std::max({e, rayint::relative_error(r.intensity[k], ref[i].intensity[k]),
                        rayint::relative_error(r.transmittance[k], ref[i].transmittance[k])});
        out.push_back(e);
      }
      return out;
    };
    auto is_on_jump = [&](std::size_t i) {
      return std::find(jc.constant_on_jump.begin(), jc.constant_on_jump.end(), i) !=
             jc.constant_on_jump.end();
    };
    auto max_error = [&](const std::string& spec, bool skip_constant_on_jump) {
      const std::vector<double> e = errors(spec);
      double worst = 0.0;
      for (std::size_t i = 0; i < e.size(); ++i)
        if (!skip_constant_on_jump || !is_on_jump(i)) worst = std::max(worst, e[i]);
      return worst;
    };
    for (const std::string spec : {"exact", "exact:path=batch"}) {
      const double e = max_error(spec, false);
      CHECK(e <= Tolerances::exact_rel);
      WARN(jc.file << ": " << spec << " vs the 50-digit reference, max rel " << e);
    }
    const double ode = max_error("ode:rtol=1e-9", false);
    CHECK(ode <= MethodTolerances::ode_error_per_rtol * 1e-9);
    // A jump inside a step costs O(jump * h): first order, so 16 times the samples must cut the
    // error by at least 4 (measured 16 to 56 from n = 128 to 2048).
    for (const std::string method : {"riemann:n=", "rk4:n=", "nerf:n=", "pl_nerf:n="}) {
      const double coarse = max_error(method + "128", false),
                   fine = max_error(method + "2048", false);
      CHECK(fine <= coarse / 4);
      WARN(jc.file << ": " << method << "128 " << coarse << ", 2048 " << fine << "; ode:rtol=1e-9 "
                   << ode);
    }
    // The pre-integrated table converges on rays that cross jumps; on a segment whose scalar sits
    // exactly on a jump it interpolates its table across the jump at every size (measured on
    // case-jumps.json: 0.59 at size 256 and at 4096; 0.25 at 2048): a limitation of sampled
    // tables, reported here and in docs/transfer-function-conventions.md, not asserted away.
    const double pre_coarse = max_error("preintegrated:size=128", true);
    const std::vector<double> pre = errors("preintegrated:size=2048");
    double pre_fine = 0.0, on_jump = 0.0;
    for (std::size_t i = 0; i < pre.size(); ++i) {
      double& worst = is_on_jump(i) ? on_jump : pre_fine;
      worst = std::max(worst, pre[i]);
    }
    CHECK(pre_fine <= pre_coarse / 4);
    WARN(jc.file << ": preintegrated crossing jumps: size 128 " << pre_coarse << ", 2048 "
                 << pre_fine << "; holding a scalar on a jump, size 2048: " << on_jump);
  }
}
