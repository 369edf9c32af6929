// VTK's tetrahedralisation of the linear cells: lookup in the recorded tables (see vtk_split.hpp).
#include "rayint/cells/vtk_split.hpp"

#include <stdexcept>

namespace rayint {
namespace {

// Lexicographic rank of the order pattern of ids[0..n-1] (Lehmer code).
int pattern_rank(const std::int64_t* ids, int n) {
  int rank = 0;
  for (int i = 0; i < n; ++i) {
    int smaller = 0;
    for (int j = i + 1; j < n; ++j) {
      if (ids[j] == ids[i]) throw std::invalid_argument("vtk_split: global ids must be distinct");
      if (ids[j] < ids[i]) ++smaller;
    }
    rank = rank * (n - i) + smaller;
  }
  return rank;
}

std::vector<std::array<int, 4>> rows(const signed char (*split)[4], int count) {
  std::vector<std::array<int, 4>> out;
  for (int k = 0; k < count && split[k][0] >= 0; ++k)
    out.push_back({split[k][0], split[k][1], split[k][2], split[k][3]});
  return out;
}

}  // namespace

std::vector<std::array<int, 4>> vtk_split(LinearCellType type, const std::int64_t* global_ids) {
  using namespace vtk_split_tables;
  const int n = linear_node_count(type);
  const int rank = pattern_rank(global_ids, n);
  switch (type) {
    case LinearCellType::tetra: return {{0, 1, 2, 3}};
    case LinearCellType::hexahedron: return rows(kHexahedronSplits[kHexahedronIndex[rank]], kMaxSplitTets);
    case LinearCellType::voxel: return rows(kVoxelSplits[kVoxelIndex[rank]], kMaxSplitTets);
    case LinearCellType::wedge: return rows(kWedgeSplits[kWedgeIndex[rank]], kMaxSplitTets);
    case LinearCellType::pyramid: return rows(kPyramidSplits[kPyramidIndex[rank]], kMaxSplitTets);
  }
  throw std::invalid_argument("vtk_split: unknown cell type");
}

std::vector<std::array<int, 4>> vtk_structured_split(LinearCellType type, int parity) {
  using namespace vtk_split_tables;
  if (parity != 0 && parity != 1) throw std::invalid_argument("vtk_structured_split: parity must be 0 or 1");
  if (type == LinearCellType::hexahedron) return rows(parity == 0 ? kHexahedronStructured0 : kHexahedronStructured1, 5);
  if (type == LinearCellType::voxel) return rows(parity == 0 ? kVoxelStructured0 : kVoxelStructured1, 5);
  throw std::invalid_argument("vtk_structured_split: structured grids have hexahedra or voxels only");
}

}  // namespace rayint
