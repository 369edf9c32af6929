// VTK's tetrahedralisation of the linear cells (see vtk_split.hpp): the placing triangulation of
// the cell's parametric points in global-id order, and VTK's fixed structured-grid tables.
#include "rayint/cells/vtk_split.hpp"

#include <algorithm>
#include <map>
#include <numeric>
#include <stdexcept>
#include <utility>

namespace rayint {
namespace {

using Tet = std::array<int, 4>;  // local node indices
using P3 = std::array<double, 3>;

// vtkHexahedron::TriangulateIds / vtkVoxel::TriangulateIds (VTK 9.1): index 0 (i + j + k even)
// and 1, as VTK 9.1 returns them (printed by scripts/cells/vtk_split_check.py; the split of the
// .vts/.vtr fixtures matches VTK's filter tet for tet, tests [cellmesh]).
constexpr Tet kHexEven[5] = {{2, 1, 5, 0}, {0, 2, 3, 7}, {2, 5, 6, 7}, {0, 7, 4, 5}, {0, 2, 7, 5}};
constexpr Tet kHexOdd[5] = {{0, 1, 3, 4}, {1, 4, 5, 6}, {1, 4, 6, 3}, {1, 3, 6, 2}, {3, 6, 7, 4}};
constexpr Tet kVoxelEven[5] = {{3, 1, 5, 0}, {0, 3, 2, 6}, {3, 5, 7, 6}, {0, 6, 4, 5}, {0, 3, 6, 5}};
constexpr Tet kVoxelOdd[5] = {{0, 1, 2, 4}, {1, 4, 5, 7}, {1, 4, 7, 2}, {1, 2, 7, 3}, {2, 7, 6, 4}};

// Parametric coordinates of the nodes (vtkVoxel, vtkHexahedron, vtkWedge, vtkPyramid), doubled so
// that every value is a small integer and every orientation test below is exact in double. The
// pyramid's apex at (1/2, 1/2, 1): its placement does not change the triangulation of the base,
// and this one gave VTK's on all 120 orders.
const std::vector<P3>& parametric(LinearCellType type) {
  static const std::vector<P3> voxel = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {2, 2, 0},
                                        {0, 0, 2}, {2, 0, 2}, {0, 2, 2}, {2, 2, 2}};
  static const std::vector<P3> hex = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0},
                                      {0, 0, 2}, {2, 0, 2}, {2, 2, 2}, {0, 2, 2}};
  static const std::vector<P3> wedge = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2}, {2, 0, 2}, {0, 2, 2}};
  static const std::vector<P3> pyramid = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {1, 1, 2}};
  switch (type) {
    case LinearCellType::voxel: return voxel;
    case LinearCellType::hexahedron: return hex;
    case LinearCellType::wedge: return wedge;
    default: return pyramid;
  }
}

P3 sub(const P3& a, const P3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
P3 cross(const P3& a, const P3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const P3& a, const P3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double orient(const P3& a, const P3& b, const P3& c, const P3& d) { return dot(sub(b, a), cross(sub(c, a), sub(d, a))); }

// How many of `simplices` contain every index of `face` (a boundary face is in exactly one).
template <std::size_t N, std::size_t M>
int containing(const std::vector<std::array<int, N>>& simplices, const std::array<int, M>& face) {
  int uses = 0;
  for (const auto& s : simplices) {
    std::size_t found = 0;
    for (int v : face) found += static_cast<std::size_t>(std::count(s.begin(), s.end(), v));
    uses += found == M ? 1 : 0;
  }
  return uses;
}

// The placing triangulation of the cell's parametric points inserted in `order`: each new point
// is joined to the faces of the current hull it sees strictly. The first points may lie in one
// plane (a face): they are triangulated in that plane first (placing in 2-D), and the first point
// off the plane is joined to every triangle.
std::vector<Tet> placing(const std::vector<P3>& x, const std::vector<int>& order) {
  const std::size_t n = order.size();
  auto at = [&](int i) -> const P3& { return x[static_cast<std::size_t>(i)]; };
  const int a = order[0], b = order[1], c = order[2];
  const P3 normal = cross(sub(at(b), at(a)), sub(at(c), at(a)));
  std::vector<std::array<int, 3>> tris = {{a, b, c}};
  std::size_t k = 3;
  for (; k < n && dot(normal, sub(at(order[k]), at(a))) == 0.0; ++k) {
    const int q = order[k];
    std::vector<std::array<int, 3>> added;
    for (const auto& t : tris)
      for (std::size_t e = 0; e < 3; ++e) {
        const int u = t[e], v = t[(e + 1) % 3], w = t[(e + 2) % 3];
        if (containing(tris, std::array<int, 2>{u, v}) != 1) continue;
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
      for (std::size_t skip = 0; skip < 4; ++skip) {
        std::array<int, 3> f{};
        for (std::size_t i = 0, j = 0; i < 4; ++i)
          if (i != skip) f[j++] = t[i];
        if (containing(tets, f) != 1) continue;
        const double sq = orient(at(f[0]), at(f[1]), at(f[2]), at(q));
        const double sw = orient(at(f[0]), at(f[1]), at(f[2]), at(t[skip]));
        if (sq * sw < 0) added.push_back({f[0], f[1], f[2], q});
      }
    tets.insert(tets.end(), added.begin(), added.end());
  }
  return tets;
}

}  // namespace

const std::vector<std::array<int, 4>>& vtk_split(LinearCellType type, const std::int64_t* global_ids) {
  static const std::vector<Tet> kTetra = {{0, 1, 2, 3}};
  if (type == LinearCellType::tetra) return kTetra;
  const int n = linear_node_count(type);
  std::vector<int> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  // A repeated id (a degenerate cell) keeps its local order: a case VTK's measurement did not cover.
  std::stable_sort(order.begin(), order.end(), [&](int x, int y) { return global_ids[x] < global_ids[y]; });
  // Templates by (type, order), as vtkOrderedTriangulator caches them: at most n! per type.
  static thread_local std::map<std::pair<int, std::vector<int>>, std::vector<Tet>> cache;
  auto key = std::make_pair(static_cast<int>(type), order);
  auto it = cache.find(key);
  if (it == cache.end()) it = cache.emplace(std::move(key), placing(parametric(type), order)).first;
  return it->second;
}

std::vector<std::array<int, 4>> vtk_structured_split(LinearCellType type, int parity) {
  if (parity != 0 && parity != 1) throw std::invalid_argument("vtk_structured_split: parity must be 0 or 1");
  const Tet* table = nullptr;
  if (type == LinearCellType::hexahedron) table = parity == 0 ? kHexEven : kHexOdd;
  if (type == LinearCellType::voxel) table = parity == 0 ? kVoxelEven : kVoxelOdd;
  if (table == nullptr)
    throw std::invalid_argument("vtk_structured_split: structured grids have hexahedra or voxels only");
  return {table, table + 5};
}

}  // namespace rayint
