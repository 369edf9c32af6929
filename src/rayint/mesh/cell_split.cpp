// vtkDataSetTriangleFilter's tetrahedralisation (see cell_split.hpp).
#include "rayint/mesh/cell_split.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <numeric>
#include <vector>

namespace rayint {
namespace {

using Tet = std::array<int, 4>;  // local node indices

// vtkHexahedron::Triangulate / vtkVoxel::Triangulate (VTK 9.1): index 0 (i + j + k even) and 1.
constexpr Tet kHexEven[5] = {{2, 1, 5, 0}, {0, 2, 3, 7}, {2, 5, 6, 7}, {0, 7, 4, 5}, {0, 2, 7, 5}};
constexpr Tet kHexOdd[5] = {{0, 1, 3, 4}, {1, 4, 5, 6}, {1, 4, 6, 3}, {1, 3, 6, 2}, {3, 6, 7, 4}};
constexpr Tet kVoxelEven[5] = {{3, 1, 5, 0}, {0, 3, 2, 6}, {3, 5, 7, 6}, {0, 6, 4, 5}, {0, 3, 6, 5}};
constexpr Tet kVoxelOdd[5] = {{0, 1, 2, 4}, {1, 4, 5, 7}, {1, 4, 7, 2}, {1, 2, 7, 3}, {2, 7, 6, 4}};

// Parametric coordinates of the nodes, doubled so that every value is a small integer and every
// orientation test below is exact in double arithmetic (vtkVoxel, vtkHexahedron, vtkWedge,
// vtkPyramid; the pyramid's apex at (1/2, 1/2, 1): the apex placement does not change the
// triangulation of the base, and this one gave VTK's on all 120 orders).
using P3 = std::array<double, 3>;
const std::vector<P3>& parametric(MeshCellType type) {
  static const std::vector<P3> voxel = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {2, 2, 0},
                                        {0, 0, 2}, {2, 0, 2}, {0, 2, 2}, {2, 2, 2}};
  static const std::vector<P3> hex = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0},
                                      {0, 0, 2}, {2, 0, 2}, {2, 2, 2}, {0, 2, 2}};
  static const std::vector<P3> wedge = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2}, {2, 0, 2}, {0, 2, 2}};
  static const std::vector<P3> pyramid = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {1, 1, 2}};
  switch (type) {
    case MeshCellType::voxel: return voxel;
    case MeshCellType::hexahedron: return hex;
    case MeshCellType::wedge: return wedge;
    default: return pyramid;
  }
}

P3 sub(const P3& a, const P3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
P3 cross(const P3& a, const P3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const P3& a, const P3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double orient(const P3& a, const P3& b, const P3& c, const P3& d) { return dot(sub(b, a), cross(sub(c, a), sub(d, a))); }

// The placing triangulation of the cell's parametric points inserted in `order`. The first points
// may lie in one plane (a face): they are triangulated in that plane first (placing in 2-D), and
// the first point off the plane is joined to every triangle.
std::vector<Tet> placing(const std::vector<P3>& x, const std::vector<int>& order) {
  const std::size_t n = order.size();
  const int a = order[0], b = order[1], c = order[2];
  const P3 normal = cross(sub(x[static_cast<std::size_t>(b)], x[static_cast<std::size_t>(a)]),
                          sub(x[static_cast<std::size_t>(c)], x[static_cast<std::size_t>(a)]));
  auto at = [&](int i) -> const P3& { return x[static_cast<std::size_t>(i)]; };
  std::vector<std::array<int, 3>> tris = {{a, b, c}};
  std::size_t k = 3;
  for (; k < n && dot(normal, sub(at(order[k]), at(a))) == 0.0; ++k) {
    const int q = order[k];
    std::vector<std::array<int, 3>> added;
    for (const auto& t : tris)
      for (int e = 0; e < 3; ++e) {
        const int u = t[static_cast<std::size_t>(e)], v = t[static_cast<std::size_t>((e + 1) % 3)],
                  w = t[static_cast<std::size_t>((e + 2) % 3)];
        int uses = 0;  // boundary edge: in one triangle only
        for (const auto& s : tris)
          uses += (std::count(s.begin(), s.end(), u) + std::count(s.begin(), s.end(), v)) == 2 ? 1 : 0;
        if (uses != 1) continue;
        const double sq = dot(normal, cross(sub(at(v), at(u)), sub(at(q), at(u))));
        const double sw = dot(normal, cross(sub(at(v), at(u)), sub(at(w), at(u))));
        if (sq * sw < 0) added.push_back({u, v, q});
      }
    tris.insert(tris.end(), added.begin(), added.end());
  }
  std::vector<Tet> tets;
  if (k == n) return tets;  // flat cell: no volume
  for (const auto& t : tris) tets.push_back({t[0], t[1], t[2], order[k]});
  for (++k; k < n; ++k) {
    const int q = order[k];
    std::vector<Tet> added;
    for (const Tet& t : tets)
      for (int skip = 0; skip < 4; ++skip) {
        std::array<int, 3> f{};
        for (int i = 0, j = 0; i < 4; ++i)
          if (i != skip) f[static_cast<std::size_t>(j++)] = t[static_cast<std::size_t>(i)];
        int uses = 0;  // boundary face: in one tetrahedron only
        for (const Tet& s : tets)
          uses += (std::count(s.begin(), s.end(), f[0]) + std::count(s.begin(), s.end(), f[1]) +
                   std::count(s.begin(), s.end(), f[2])) == 3 ? 1 : 0;
        if (uses != 1) continue;
        const int w = t[static_cast<std::size_t>(skip)];
        const double sq = orient(at(f[0]), at(f[1]), at(f[2]), at(q));
        const double sw = orient(at(f[0]), at(f[1]), at(f[2]), at(w));
        if (sq * sw < 0) added.push_back({f[0], f[1], f[2], q});
      }
    tets.insert(tets.end(), added.begin(), added.end());
  }
  return tets;
}

// Templates by (type, order of the local nodes by global id), as vtkOrderedTriangulator caches them.
const std::vector<Tet>& ordered_template(MeshCellType type, const std::vector<int>& order) {
  static thread_local std::map<std::pair<int, std::vector<int>>, std::vector<Tet>> cache;
  const auto key = std::make_pair(static_cast<int>(type), order);
  auto it = cache.find(key);
  if (it == cache.end()) it = cache.emplace(key, placing(parametric(type), order)).first;
  return it->second;
}

}  // namespace

TetMesh split_cells(const CellMesh& mesh, CellSplitCounts* counts) {
  TetMesh out;
  out.points = mesh.points;
  out.scalars = mesh.scalars;
  out.info = mesh.info;
  out.info.cell_ids.clear();
  CellSplitCounts local;
  CellSplitCounts& n = counts != nullptr ? *counts : local;
  n.structured = mesh.structured.has_value();
  const bool cell_data = !mesh.cell_scalars.empty();
  auto file_id = [&](std::size_t c) {
    return c < mesh.info.cell_ids.size() ? mesh.info.cell_ids[c] : static_cast<long long>(c);
  };
  auto emit = [&](std::size_t c, const std::int32_t* p, const Tet& t) {
    out.tets.push_back({p[t[0]], p[t[1]], p[t[2]], p[t[3]]});
    out.info.cell_ids.push_back(file_id(c));
    if (cell_data) out.cell_scalars.push_back(mesh.cell_scalars[c]);
    ++n.tets[mesh_cell_name(mesh.types[c])];
  };
  std::vector<int> order;
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    const MeshCellType type = mesh.types[c];
    const std::int32_t* p = mesh.cell(c);
    ++n.cells[mesh_cell_name(type)];
    if (type == MeshCellType::tetra) {
      emit(c, p, {0, 1, 2, 3});
      continue;
    }
    if (mesh.structured) {
      const auto& d = *mesh.structured;
      const std::size_t cx = static_cast<std::size_t>(d[0] - 1), cy = static_cast<std::size_t>(d[1] - 1);
      const std::size_t i = c % cx, j = (c / cx) % cy, k = c / (cx * cy);
      const bool even = (i + j + k) % 2 == 0;
      const Tet* table = type == MeshCellType::voxel ? (even ? kVoxelEven : kVoxelOdd) : (even ? kHexEven : kHexOdd);
      for (int t = 0; t < 5; ++t) emit(c, p, table[t]);
      continue;
    }
    const std::size_t nodes = mesh.nodes_of(c);
    order.resize(nodes);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int x, int y) { return p[x] < p[y]; });
    for (const Tet& t : ordered_template(type, order)) emit(c, p, t);
  }
  return out;
}

}  // namespace rayint
