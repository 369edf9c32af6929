// rayint's VTK XML readers (input/vtk_xml_reader.hpp, tag [vtkxml]) on files VTK and meshio wrote
// (tests/fixtures/vtkxml/, by generate.py). The oracle is VTK itself: generate.py read every file
// back with vtkXMLUnstructuredGridReader / vtkXMLImageDataReader and dumped what VTK read into
// expected.json; every file, in every data mode, encoding, compressor, header type, byte order and
// id type, must read to exactly (bit for bit) those points, cells and point arrays. Then: a mesh
// case naming a .vtu evaluates like the same mesh as VTK's legacy .vtk; a .vti is a scene's
// grid_file; bad input is one line naming the file and the field (exit 2, no output file).
// mesh-legacy.vtk is VTK 9.1's legacy 5.1 output with METADATA blocks (each ended by a blank
// line), which the legacy reader used to run past (it skipped the blank line): "CELLS: missing".
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "test_paths.hpp"
#include "cli_harness.hpp"
#include "rayint/core/error.hpp"
#include "rayint/input/mesh_case_reader.hpp"
#include "rayint/input/voxel_grid_reader.hpp"
#include "rayint/input/vtk_xml_reader.hpp"
#include "input_text.hpp"

using namespace rayint;
using rayint::test::run_cli;
using rayint::test::slurp;
using rayint::test::TempDir;
namespace fs = std::filesystem;

namespace {

const fs::path kDir = fs::path(RAYINT_SOURCE_DIR) / "tests" / "fixtures" / "vtkxml";

const nlohmann::json& expected() {
  static const nlohmann::json j = nlohmann::json::parse(slurp(kDir / "expected.json"));
  return j;
}

std::vector<std::string> files_of(const std::string& ext) {
  std::vector<std::string> out;
  for (const auto& [file, group] : expected()["files"].items())
    if (fs::path(file).extension() == ext) out.push_back(file);
  return out;
}

std::string replace_once(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  REQUIRE(at != std::string::npos);
  return s.replace(at, from.size(), to);
}

void expect_error(const std::string& message, const std::string& prefix, const std::string& contains = "") {
  INFO(message);
  CHECK(message.rfind(prefix, 0) == 0);
  CHECK(message.find('\n') == std::string::npos);
  if (!contains.empty()) CHECK(message.find(contains) != std::string::npos);
}

}  // namespace

TEST_CASE("every .vtu VTK and meshio wrote reads to what VTK's own reader read, bit for bit", "[vtkxml]") {
  const auto files = files_of(".vtu");
  REQUIRE(files.size() == 16);  // 15 vtkXMLUnstructuredGridWriter variants + meshio
  for (const std::string& file : files) {
    const nlohmann::json& want = expected()["groups"][expected()["files"][file].get<std::string>()];
    const std::string path = (kDir / file).string();
    INFO(file);
    std::size_t arrays_read = 0;
    for (const auto& [name, array] : want["point_arrays"].items()) {
      if (array["components"] != 1) {
        expect_error(rayint::test::input_error_of([&] { read_vtu(path, {name}); }), path + ": UnstructuredGrid/Piece/PointData: array \"" + name + "\" has 3 components; the scalar needs 1");
        continue;
      }
      INFO(name);
      const TetMesh m = read_vtu(path, {name});
      REQUIRE(m.points.size() == want["points"].size());
      REQUIRE(m.tets.size() == want["cells"].size());
      for (std::size_t i = 0; i < m.points.size(); ++i)
        for (int k = 0; k < 3; ++k) CHECK(m.points[i][k] == want["points"][i][static_cast<std::size_t>(k)].get<double>());
      for (std::size_t i = 0; i < m.tets.size(); ++i) {
        REQUIRE(want["cell_types"][i] == 10);
        for (std::size_t k = 0; k < 4; ++k) CHECK(m.tets[i][k] == want["cells"][i][k].get<std::int64_t>());
      }
      const auto& values = array["values"];
      REQUIRE(m.scalars.size() == values.size());
      for (std::size_t i = 0; i < values.size(); ++i) CHECK(m.scalars[i] == values[i].get<double>());
      ++arrays_read;
    }
    CHECK(arrays_read == (file == "mesh-meshio.vtu" ? 1U : 5U));  // s, f32, i32, i64, u8
    // No name: VTK's active scalars (PointData Scalars="s"), else the first one-component array.
    const TetMesh by_default = read_vtu(path);
    const auto& s = want["point_arrays"]["s"]["values"];
    for (std::size_t i = 0; i < s.size(); ++i) CHECK(by_default.scalars[i] == s[i].get<double>());
  }
}

TEST_CASE("every .vti VTK wrote reads to VTK's grid and point arrays, bit for bit", "[vtkxml][grid]") {
  const auto files = files_of(".vti");
  REQUIRE(files.size() == 15);  // 14 variants + image-direction.vti
  for (const std::string& file : files) {
    const std::string path = (kDir / file).string();
    INFO(file);
    if (file == "image-direction.vti") {
      // Placed as VTK placed it: VTK's first and last points (vtkImageData::GetPoint, which
      // applies the Direction) are Origin + Direction (grid point - Origin).
      const nlohmann::json& want = expected()["groups"]["image-direction"];
      const VoxelGrid g = read_vti(path);
      const GridPlacement& p = g.placement();
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) CHECK(p.direction(r, c) == want["direction"][static_cast<std::size_t>(3 * r + c)].get<double>());
      const Vec3 first = p.pivot + p.direction * (g.lower() - p.pivot);
      const Vec3 last = p.pivot + p.direction * (g.upper() - p.pivot);
      for (int a = 0; a < 3; ++a) {
        const double f = want["point_first"][static_cast<std::size_t>(a)].get<double>();
        const double l = want["point_last"][static_cast<std::size_t>(a)].get<double>();
        CHECK(std::abs(first[a] - f) <= 8 * std::numeric_limits<double>::epsilon() * (1.0 + std::abs(f)));
        CHECK(std::abs(last[a] - l) <= 8 * std::numeric_limits<double>::epsilon() * (1.0 + std::abs(l)));
      }
      CHECK(g.values() == read_vti((kDir / "image-ascii.vti").string()).values());
      continue;
    }
    const nlohmann::json& want = expected()["groups"]["image"];
    for (const auto& [name, array] : want["point_arrays"].items()) {
      INFO(name);
      const VoxelGrid g = read_vti(path, name);
      for (int a = 0; a < 3; ++a) {
        const auto lo = want["extent"][static_cast<std::size_t>(2 * a)].get<int>();
        const auto hi = want["extent"][static_cast<std::size_t>(2 * a + 1)].get<int>();
        CHECK(g.dims()[static_cast<std::size_t>(a)] == hi - lo + 1);
        CHECK(g.spacing()[a] == want["spacing"][static_cast<std::size_t>(a)].get<double>());
        // VTK's point (i, j, k) of the extent: origin + i * spacing (vtkImageData::GetPoint)
        CHECK(g.origin()[a] == want["point_first"][static_cast<std::size_t>(a)].get<double>());
        // the far corner: VoxelGrid adds (dims - 1) * spacing to the corner, VTK multiplies from
        // Origin; the two roundings may differ by an ulp or two
        const double last = want["point_last"][static_cast<std::size_t>(a)].get<double>();
        CHECK(std::abs(g.upper()[a] - last) <= 4 * std::numeric_limits<double>::epsilon() * std::abs(last));
      }
      const auto& values = array["values"];
      REQUIRE(g.values().size() == values.size());
      for (std::size_t i = 0; i < values.size(); ++i) CHECK(g.values()[i] == values[i].get<double>());
    }
    CHECK(read_vti(path).values() == read_vti(path, "s").values());  // active scalars by default
  }
}

TEST_CASE("a mesh case naming a .vtu evaluates like the same mesh as VTK's legacy .vtk", "[vtkxml][mesh][cli]") {
  TempDir dir;
  const std::string kCase = R"({
  "name": "vtkxml",
  "transfer_function": {"density": [[-0.5, 0.5], [0.2, 3.0], [0.7, 0.2], [1.2, 5.0]],
                        "color": [[-0.4, 1.0], [0.5, 0.2], [1.3, 1.5]]},
  "mesh_file": "m.vtk",
  "background": [0.2, 0.1, 0.05],
  "rays": [{"origin": [0.1, 0.2, 4], "direction": [0, 0, -1]},
           {"origin": [-4, -3, 2], "direction": [4, 3.1, -2.2]},
           {"origin": [3, 3, 3], "direction": [-1, -1, -1]}],
  "camera": {"position": [2.5, 2, 3.5], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov_deg": 40, "width": 16, "height": 12}
})";
  fs::copy_file(kDir / "mesh-legacy.vtk", dir.path / "m.vtk");
  dir.write("legacy.json", kCase);
  const auto want = run_cli(dir.path, "eval legacy.json --methods exact --no-timing");
  INFO(want.err);
  REQUIRE(want.status == 0);
  for (const std::string file : {"mesh-ascii.vtu", "mesh-appended-raw-zlib-be.vtu", "mesh-meshio.vtu"}) {
    fs::copy_file(kDir / file, dir.path / "m.vtu", fs::copy_options::overwrite_existing);
    dir.write("xml.json", replace_once(kCase, "m.vtk", "m.vtu"));
    const auto got = run_cli(dir.path, "eval xml.json --methods exact --no-timing");
    INFO(file << ": " << got.err);
    REQUIRE(got.status == 0);
    std::string norm = got.out;
    for (auto at = norm.find("m.vtu"); at != std::string::npos; at = norm.find("m.vtu")) norm.replace(at, 5, "m.vtk");
    for (auto at = norm.find("xml.json"); at != std::string::npos; at = norm.find("xml.json")) norm.replace(at, 8, "legacy.json");
    CHECK(norm == want.out);
  }
}

TEST_CASE("a scene's grid_file may be a .vti", "[vtkxml][grid]") {
  const std::string path = (kDir / "image-appended-base64-zlib-h64.vti").string();
  const VoxelGrid a = read_voxel_grid_file(path);
  const VoxelGrid b = read_vti(path, "s");
  CHECK(a.values() == b.values());
  CHECK(a.dims() == b.dims());
}

TEST_CASE("bad VTK XML input: one line naming the file and the field", "[vtkxml][bad_input]") {
  const std::string src = "bad.vtu";
  const auto vtu = [&](const std::string& text, const std::string& name = "") {
    return rayint::test::input_error_of([&] { parse_vtu(text, src, {name}); });
  };
  const std::string pts = src + ": UnstructuredGrid/Piece/Points/DataArray: ";
  const std::string binary = slurp(kDir / "mesh-binary.vtu");
  const std::string raw = slurp(kDir / "mesh-appended-raw.vtu");
  const std::string zraw = slurp(kDir / "mesh-appended-raw-zlib.vtu");
  const std::string ascii = slurp(kDir / "mesh-ascii.vtu");

  SECTION("truncated base64") {
    const auto start = binary.find('>', binary.find("<DataArray type=\"Float64\" Name=\"Points\"")) + 1;
    const auto end = binary.find("</DataArray>", start);
    std::string cut = binary;
    cut.erase(start + (end - start) / 2, end - start - (end - start) / 2);
    expect_error(vtu(cut), pts, "truncated");
  }
  SECTION("invalid base64 character") {
    const auto start = binary.find('>', binary.find("<DataArray type=\"Float64\" Name=\"Points\"")) + 30;
    std::string bad = binary;
    bad[start] = '*';
    expect_error(vtu(bad), pts, "invalid base64 character '*'");
  }
  SECTION("wrong offsets") {
    const auto at = raw.find("offset=\"", raw.find("Name=\"Points\"")) + 8;
    std::string bad = raw;
    bad.replace(at, raw.find('"', at) - at, "999999");
    expect_error(vtu(bad), pts, "offset 999999 is beyond the AppendedData");
    bad = raw;
    bad.replace(at, raw.find('"', at) - at, "1");  // inside another array: its header is garbage
    expect_error(vtu(bad), pts, "header says");
  }
  SECTION("header size beyond the file") {
    std::string bad = raw;
    bad.erase(bad.rfind("</AppendedData>") - 100, 100);  // the last array (types) loses its end
    expect_error(vtu(bad), src + ": UnstructuredGrid/Piece/Cells/DataArray[types]: ", "data truncated");
  }
  SECTION("bad zlib stream and compression header") {
    // Points' appended block: header [nblocks, block, last, csize...] (UInt32), then zlib streams.
    const auto at = zraw.find("offset=\"", zraw.find("Name=\"Points\"")) + 8;
    const std::size_t offset = std::stoul(zraw.substr(at, zraw.find('"', at) - at));
    const std::size_t data = zraw.find('_', zraw.find("<AppendedData")) + 1 + offset;
    const auto nblocks = static_cast<unsigned char>(zraw[data]);
    REQUIRE(nblocks == 3);  // 1536 bytes in 512-byte blocks
    std::string bad = zraw;
    for (std::size_t i = 0; i < 8; ++i) bad[data + 4 * (3 + nblocks) + 2 + i] ^= '\x5a';
    expect_error(vtu(bad), pts, "compressed block 0: ");
    bad = zraw;
    bad[data + 4] = '\x01';  // block size 513: 3 blocks no longer hold 1536 bytes
    expect_error(vtu(bad), pts, "compression header: 3 blocks of 513 bytes");
    bad = zraw;
    bad[data + 4 * 3 + 1] = '\x7f';  // the first block's compressed size beyond the file
    expect_error(vtu(bad), pts, "compressed block 0: ");
  }
  SECTION("unknown type, format, compressor, header type, byte order") {
    expect_error(vtu(replace_once(ascii, "type=\"Float64\" Name=\"Points\"", "type=\"Float128\" Name=\"Points\"")), pts,
                 "type \"Float128\" is not read");
    expect_error(vtu(replace_once(ascii, "format=\"ascii\"", "format=\"hex\"")), src + ": UnstructuredGrid/Piece/PointData/DataArray[s]: format \"hex\"");
    // A zlib stream handed to the LZ4 and LZMA decoders: refused by the decoder, one line.
    expect_error(vtu(replace_once(zraw, "vtkZLibDataCompressor", "vtkLZ4DataCompressor")), src + ": UnstructuredGrid/Piece/Points/DataArray: compressed block 0: ");
    expect_error(vtu(replace_once(zraw, "vtkZLibDataCompressor", "vtkLZMADataCompressor")), src + ": UnstructuredGrid/Piece/Points/DataArray: compressed block 0: ");
    expect_error(vtu(replace_once(zraw, "vtkZLibDataCompressor", "vtkBZip2DataCompressor")), src + ": VTKFile: compressor \"vtkBZip2DataCompressor\" is not read");
    expect_error(vtu(replace_once(raw, "header_type=\"UInt32\"", "header_type=\"UInt16\"")), src + ": VTKFile: header_type \"UInt16\"");
    expect_error(vtu(replace_once(raw, "LittleEndian", "MiddleEndian")), src + ": VTKFile: byte_order \"MiddleEndian\"");
  }
  SECTION("missing fields") {
    expect_error(vtu(replace_once(ascii, "Name=\"types\"", "Name=\"typez\"")), src + ": UnstructuredGrid/Piece/Cells/DataArray[types]: missing");
    expect_error(vtu(replace_once(replace_once(ascii, "<Points>", "<Pointz>"), "</Points>", "</Pointz>")), src + ": UnstructuredGrid/Piece/Points: missing");
    expect_error(vtu(replace_once(ascii, "NumberOfPoints", "NumberOfPointz")), src + ": UnstructuredGrid/Piece: missing attribute NumberOfPoints");
    expect_error(vtu(ascii, "pressure"), src + ": UnstructuredGrid/Piece/PointData: no array named \"pressure\"");
    expect_error(vtu(replace_once(ascii, "type=\"UnstructuredGrid\"", "type=\"PolyData\"")), src + ": VTKFile: type \"PolyData\" is not read");
    expect_error(vtu("not xml at all"), src + ": XML: No document element");
    expect_error(vtu("<?xml version=\"1.0\"?><Other/>"), src + ": VTKFile: missing");
    expect_error(vtu("<VTKFile"), src + ": XML: ");
    expect_error(vtu(""), src + ": XML: ");
  }
  SECTION("wrong counts and values") {
    expect_error(vtu(replace_once(ascii, "NumberOfPoints=\"64\"", "NumberOfPoints=\"65\"")), pts, "has 192 values, expected 195");
    expect_error(vtu(replace_once(raw, "NumberOfPoints=\"64\"", "NumberOfPoints=\"4000000000\"")), src + ": UnstructuredGrid/Piece: NumberOfPoints");
    expect_error(vtu(replace_once(zraw, "NumberOfPoints=\"64\"", "NumberOfPoints=\"6400000\"")), pts, "do not hold the expected");
    const auto types = ascii.find('>', ascii.find("Name=\"types\"")) + 1;
    std::string hex = ascii;
    hex.replace(hex.find("10", types), 2, "12");
    expect_error(vtu(hex), src + ": UnstructuredGrid/Piece/Cells/DataArray[types][0]: cell type hexahedron (VTK id 12): the tetrahedral path integrates only tetrahedra; integrate this file with --cells split");
    const auto conn = ascii.find('>', ascii.find("Name=\"connectivity\"")) + 1;
    std::string oob = ascii;
    oob.insert(ascii.find_first_not_of(" \n", conn), "64");  // first index becomes 64x
    expect_error(vtu(oob), src + ": UnstructuredGrid/Piece/Cells/DataArray[connectivity]: value 0");
  }
  SECTION("image data") {
    const std::string vti = slurp(kDir / "image-ascii.vti");
    const auto img = [&](const std::string& text) { return rayint::test::input_error_of([&] { parse_vti(text, "bad.vti"); }); };
    expect_error(img(replace_once(vti, "Spacing=\"0.5", "Spacing=\"-0.5")), "bad.vti: ImageData: Spacing must be > 0");
    expect_error(img(replace_once(vti, "WholeExtent=\"1 5", "WholeExtent=\"1 1")), "bad.vti: ImageData: WholeExtent");
    expect_error(img(replace_once(vti, "<Piece Extent=\"1 5 0 3 2 4\"", "<Piece Extent=\"1 4 0 3 2 4\"")),
                 "bad.vti: ImageData/Piece: Extent differs");
    expect_error(img(replace_once(vti, "Origin=\"-0.25", "Origin=\"nan")), "bad.vti: ImageData: Origin");
    expect_error(img(replace_once(vti, "0.7237499999999999", "inf")), "bad.vti: ImageData/Piece/PointData/DataArray[s]: value 0 is not finite");
  }
}

TEST_CASE("CLI: a bad .vtu in a mesh case exits 2 with one line and leaves no output", "[vtkxml][cli][bad_input]") {
  TempDir dir;
  std::string text = slurp(kDir / "mesh-binary-zlib.vtu");
  text.resize(text.size() / 2);
  dir.write("m.vtu", text);
  dir.write("c.json", R"({"name": "c", "transfer_function": {"density": [[0, 1], [1, 2]], "color": [[0, 1], [1, 1]]},
    "mesh_file": "m.vtu", "rays": [{"origin": [0, 0, 5], "direction": [0, 0, -1]}]})");
  const auto before = dir.entries();
  const auto r = run_cli(dir.path, "eval c.json -o out.json");
  INFO(r.err);
  CHECK(r.status == 2);
  CHECK(r.out.empty());
  CHECK(r.err.rfind("rayint: error: m.vtu: ", 0) == 0);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK(dir.entries() == before);
}
