#pragma once
// Checks of a tetrahedral mesh as read, for `rayint mesh info [--check]` and the mesh case reader:
// orientation counts and overlapping tetrahedra.
//
// Overlap (issue 27): two meshes appended without shared points (ParaView's Append Datasets of
// overlapping meshes) give tets whose interiors intersect; traversal would integrate the shared
// volume twice, or take one of them at random at a face, so such a mesh is refused. The test:
//   candidates  every pair of tets whose bounding boxes overlap by more than the tolerance, found
//               with a uniform grid of the boxes (cell size: the mean box extent), filled by a
//               counting sort; a pair is visited once, in the grid cell that holds the lower corner
//               of the boxes' intersection (per cell, the members are split by the axes on which
//               they start there, and only lists that start on all three axes together are paired);
//   exact test  separating axes for two convex polyhedra: the 4 face normals of each tet and the
//               36 cross products of their edges; the interiors are disjoint iff on some axis the
//               two projections overlap by at most the tolerance (touching is not overlapping, so
//               tets sharing a face, an edge or a point pass). The line through the two centroids
//               is tried first: it settles most neighbours, and cannot change the answer (the
//               smallest overlap over all directions is attained on one of the 44 axes).
// Tolerance: kOverlapTolerance x the larger box diagonal of the pair, on unit axes. Rounding of
// the projections is ~1e-16 of that, so conforming meshes pass with margin; an overlap thinner
// than the tolerance (1e-9 of the cells' size) is not detected. Tests ([mesh][check]): VTK's
// Append of two shifted boxes is found; gmsh's, TetGen's and the generated meshes (ball-100k:
// 105,456 tets) pass.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>

#include "rayint/mesh/tet_mesh.hpp"

namespace rayint {

inline constexpr double kOverlapTolerance = 1e-9;

struct OrientationCounts {
  long positive = 0, inverted = 0, zero_volume = 0, slivers = 0;
};
OrientationCounts orientation_counts(const TetMesh& mesh);

// True when the interiors of tets a and b intersect (by more than the tolerance above).
bool tets_overlap(const TetMesh& mesh, std::size_t a, std::size_t b);

// Which candidate pairs are tested: all of them (`rayint mesh info --check`), or only those that
// share no point (what every mesh case does on load: it finds meshes appended without shared
// points, the overlap issue 27 met in practice, at a fraction of the cost, because the
// neighbours that share points are most of the candidates). Cost on load, CPU per tet:
// reports/scaling/README.md (1.6 us per tet on the 105k-tet ball, from 5.6 before issue 33).
enum class OverlapScope { all_pairs, disjoint_pairs };

// The first overlapping pair (a < b) found, or nothing.
std::optional<std::pair<std::size_t, std::size_t>> find_overlapping_tets(const TetMesh& mesh,
                                                                          OverlapScope scope = OverlapScope::all_pairs);

// Throws InputError "<source>: <tets>: tetrahedra A and B overlap (...)" naming the two cells as
// the file numbers them (MeshFileInfo::cell_ids when the reader recorded them). Tests the pairs
// that share no point (OverlapScope::disjoint_pairs).
void refuse_overlapping_tets(const TetMesh& mesh, const std::string& source, const std::string& tets_field);

}  // namespace rayint
