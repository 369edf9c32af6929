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

#include "rayint/mesh/tet_adjacency.hpp"
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
// reports/scaling/README.md and NOTES.md; on load the boundary fast path below runs first.
enum class OverlapScope { all_pairs, disjoint_pairs };

// The first overlapping pair (a < b) found, or nothing.
std::optional<std::pair<std::size_t, std::size_t>> find_overlapping_tets(const TetMesh& mesh,
                                                                          OverlapScope scope = OverlapScope::all_pairs);

// Throws InputError "<source>: <tets>: tetrahedra A and B overlap (...)" naming the two cells as
// the file numbers them (MeshFileInfo::cell_ids when the reader recorded them). Tests the pairs
// that share no point (OverlapScope::disjoint_pairs).
void refuse_overlapping_tets(const TetMesh& mesh, const std::string& source, const std::string& tets_field);

// The load check's fast path (issue 33). It rests on this
//
// LEMMA. Let M be a finite set of tetrahedra of positive volume in which every face (a triple of
// point indices) belongs to at most two tets, and the two tets of a shared face lie on opposite
// sides of it, and let e be any direction. If the interiors of two tets of M intersect, then
// some tet T has a boundary face F (a face of T alone) whose outward normal n has n . e > 0, and
// a point y of F lies in the closure of another tet X whose interior meets T's interior.
//
// PROOF. Let U be the set of points in the interiors of at least two tets: open, bounded and, by
// hypothesis, not empty. Every point y of its frontier lies on a face of some tet (otherwise the
// number of tets whose interior holds the points near y would be constant near y, and >= 2,
// putting y in U). On each line parallel to e that meets U take the last point y of the closure
// of U: these points project (along e) onto the projection of U (an open set, so of positive
// area), while the points on tet edges, on the lines where two face planes cross and on faces
// parallel to e project onto a set of zero area, whatever e is. So there is such a y in the
// relative interior of a face with plane P, on no edge, on faces (only) lying in P, and P is not
// parallel to e. In a small ball around y every tet either holds the whole ball (set I; |I| <= 1
// since y is not in U), misses it, or holds exactly one half-ball, having a face in P through y
// (sets H+ and H- by side). U holds the half-ball B- before y (on the side e comes from) but not
// B+, so |I| + |H-| >= 2 and |I| + |H+| <= 1. A face through y shared by two tets has them on
// opposite sides, and a tet has one face in P, so pairing a tet of H- with the tet across its
// face at y is one to one into H+. If |I| = 1, H+ is empty, so H- (>= 1 tet) has a tet T whose
// face F at y is a boundary face, and X, the tet of I, holds y and B-. If |I| = 0,
// |H-| >= 2 > |H+|, so some T in H- has no partner: its face F at y is a boundary face, and X,
// another tet of H-, has y on its face and holds B-. T holds B-, which lies on the side of P
// that e comes from, so F's outward normal n has n . e > 0; X's interior holds B-, as T's does. []
//
// The premises hold after tet_neighbors (shared faces: at most two tets, opposite sides) and
// validate or repair (no tet of zero volume or a sliver). So, for one fixed e (kSweep in
// mesh_check.cpp, parallel to no face of a box or a Kuhn mesh), the fast path tests only the
// pairs (T, X) with T a tet with a boundary face F facing e and X another tet whose closed box
// meets F's closed box (y lies in both; exact: coordinates are only compared), point-sharing ones
// included (face neighbours excepted: the adjacency found them on opposite sides), with the exact
// test above on T and X. A face is left out only when n . e <= 0 is certain under a bound on the
// rounding of n . e and of the side of T (mesh_check.cpp, facing_faces); a tet with several such
// faces is tested once, against the box of their points. No overlap there proves no overlap
// anywhere, and the mesh passes. If one is found (a fold inside one mesh may be point-sharing
// only), the full check decides, so the answer is always the full check's. On the 105k ball (8112
// boundary faces) this is 99k exact tests, from 137k pairs of boxes that meet (before: every
// boundary tet against the tets whose boxes meet its box, 315k exact tests). Cost: one box and
// one look-up of 8 summed cell counts per tet, the cells and the exact tests only for the tets
// near a facing boundary face; reports/scaling/README.md. Limits: the lemma is exact; the pair
// test has the tolerance above, so an overlap thinner than 1e-9 of the cells' size near the
// boundary, with a deeper one inside, would be missed by the fast path alone (none is known).
// Tests ([mesh][scaling]): against the full check on appended, shifted, touching and nested
// meshes sharing no points, folds at the boundary and meshes touching themselves.
//
// True when no tet with a boundary face facing e overlaps another tet whose box meets that face's
// box: by the lemma, no two tets overlap. `next` is tet_neighbors(mesh); false (undecided) when
// it does not match.
bool boundary_tets_overlap_free(const TetMesh& mesh, const TetNeighbors& next);

// find_overlapping_tets and refuse_overlapping_tets with the fast path first: the same answers.
std::optional<std::pair<std::size_t, std::size_t>> find_overlapping_tets(const TetMesh& mesh, const TetNeighbors& next,
                                                                          OverlapScope scope);
void refuse_overlapping_tets(const TetMesh& mesh, const TetNeighbors& next, const std::string& source,
                             const std::string& tets_field);

}  // namespace rayint
