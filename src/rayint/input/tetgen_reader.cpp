// TetGen .node/.ele reader (see tetgen_reader.hpp).
#include "rayint/input/tetgen_reader.hpp"

#include <array>
#include <cstdint>
#include <filesystem>

#include "rayint/cells/cell_types.hpp"
#include "rayint/core/error.hpp"
#include "rayint/input/json_source.hpp"
#include "rayint/input/mesh_text.hpp"

namespace rayint {
namespace {

constexpr long long kMaxCount = 2'000'000'000;  // indices are stored as int32

std::string at(const char* field, std::size_t i) { return std::string(field) + "[" + std::to_string(i) + "]"; }

// The index `word` of line i of a .node or .ele list (field f): TetGen numbers the lines from 0 or 1,
// as the first line says (then kept in `base`), one by one.
void check_line_index(const mesh_text::LineCursor& c, std::string_view word, const std::string& f, std::size_t i,
                      long long& base) {
  const long long index = c.integer(word, f, -kMaxCount, kMaxCount);
  if (i == 0) {
    if (index != 0 && index != 1) c.fail(f, "the first index must be 0 or 1, got " + std::to_string(index));
    base = index;
  } else if (index != base + static_cast<long long>(i)) {
    c.fail(f, "index " + std::to_string(index) + " out of sequence (expected " +
                  std::to_string(base + static_cast<long long>(i)) + ")");
  }
}

}  // namespace

TetMesh parse_tetgen(std::string_view node_bytes, const std::string& node_source,
                     std::string_view ele_bytes, const std::string& ele_source,
                     const std::string& scalar_name) {
  TetMesh mesh;
  // .node
  mesh_text::LineCursor n(node_bytes, node_source, '#');
  auto h = n.need_words("header", 1, "<points> 3 <attributes> <markers>");
  const auto points = static_cast<std::size_t>(n.integer(h[0], "header", 0, kMaxCount));
  if (h.size() >= 2 && n.integer(h[1], "header", 0, 3) != 3) n.fail("header", "dimension must be 3");
  const auto attributes = h.size() >= 3 ? static_cast<std::size_t>(n.integer(h[2], "header", 0, 1000)) : 0;
  const auto markers = h.size() >= 4 ? static_cast<std::size_t>(n.integer(h[3], "header", 0, 1)) : 0;
  if (points == 0) n.fail("header", "no points");
  std::size_t which = 0;
  if (!scalar_name.empty()) {
    which = static_cast<std::size_t>(n.integer(scalar_name, "scalar_field", 0, 999));
    if (which >= attributes)
      n.fail("header", "scalar_field \"" + scalar_name + "\": the file has " + std::to_string(attributes) +
                           " point attributes");
  } else if (attributes == 0) {
    n.fail("header", "no point attributes (rayint takes the scalar at each point from the first attribute; the"
                     " boundary markers and region attributes are labels, not a field)");
  }
  mesh.points.reserve(mesh_text::reserve_bound(points, n.remaining_bytes(), 8));
  mesh.scalars.reserve(mesh.points.capacity());
  long long base = 0;
  for (std::size_t i = 0; i < points; ++i) {
    const std::string f = at("node", i);
    const auto w = n.need_words(f, 4 + attributes + markers, "index x y z [attributes] [marker]");
    check_line_index(n, w[0], f, i, base);
    mesh.points.emplace_back(n.real(w[1], f), n.real(w[2], f), n.real(w[3], f));
    mesh.scalars.push_back(n.real(w[4 + which], f));
  }
  // .ele
  mesh_text::LineCursor e(ele_bytes, ele_source, '#');
  h = e.need_words("header", 1, "<tets> <4|10> <attributes>");
  const auto tets = static_cast<std::size_t>(e.integer(h[0], "header", 0, kMaxCount));
  const auto per_tet = h.size() >= 2 ? e.integer(h[1], "header", 4, 10) : 4;
  if (per_tet != 4 && per_tet != 10) e.fail("header", "nodes per tetrahedron must be 4 or 10");
  // One rule for every reader (cells/cell_types.hpp): a 10-node tetrahedron (tetgen -o2) is a
  // quadratic tetra, read as its corners with its mid-edge nodes in VTK's order
  // (kTetgenTet10ToVtk) and integrated with its quadratic interpolation.
  const auto region = h.size() >= 3 ? static_cast<std::size_t>(e.integer(h[2], "header", 0, 1000)) : 0;
  if (tets == 0) e.fail("header", "no tetrahedra");
  mesh.tets.reserve(mesh_text::reserve_bound(tets, e.remaining_bytes(), 10));
  long long ele_base = 0;
  for (std::size_t i = 0; i < tets; ++i) {
    const std::string f = at("ele", i);
    const auto w = e.need_words(f, 1 + static_cast<std::size_t>(per_tet) + region, "index n1 n2 n3 n4 [...]");
    check_line_index(e, w[0], f, i, ele_base);
    std::array<std::int32_t, 10> v{};
    for (std::size_t k = 0; k < static_cast<std::size_t>(per_tet); ++k)
      v[k] = static_cast<std::int32_t>(
          e.integer(w[1 + static_cast<std::size_t>(kTetgenTet10ToVtk[k])], f, base, base + static_cast<long long>(points) - 1) - base);
    mesh.tets.push_back({v[0], v[1], v[2], v[3]});
    if (per_tet == 10) mesh.edge_nodes.push_back({v[4], v[5], v[6], v[7], v[8], v[9]});
  }
  mesh.info.cells_by_type[per_tet == 10 ? "quadratic tetra" : "tetra"] = static_cast<long>(mesh.tets.size());
  for (std::size_t a = 0; a < attributes; ++a)
    mesh.info.arrays.push_back({"attribute " + std::to_string(a), "point", 1, false});
  if (markers > 0) mesh.info.arrays.push_back({"boundary marker", "point", 1, true});
  if (region > 0) mesh.info.arrays.push_back({"region attribute", "cell", static_cast<long>(region), true});
  mesh.info.scalar = "attribute " + std::to_string(which);
  validate_tet_mesh_structure(mesh, ele_source, MeshFieldNames{"node", "node attribute", "ele"});
  return mesh;
}

TetMesh read_tetgen(const std::string& ele_path, const std::string& scalar_name) {
  std::filesystem::path node = ele_path;
  node.replace_extension(".node");
  const std::string ele_text = json_source::read_text_file(ele_path);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(node, ec))
    throw InputError(ele_path + ": node: no .node file beside it (" + node.string() + ")");
  const std::string node_text = json_source::read_text_file(node.string());
  return parse_tetgen(node_text, node.string(), ele_text, ele_path, scalar_name);
}

}  // namespace rayint
