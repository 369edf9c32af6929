#pragma once
// Face adjacency of a tetrahedral mesh: the tet across each face. Computed once per load (issue 33)
// and shared by the overlap check (mesh/mesh_check.hpp, which needs the boundary faces) and the
// traversal build (mesh/tet_traversal.hpp), which takes it instead of sorting the faces again.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "rayint/mesh/tet_mesh.hpp"

namespace rayint {

// neighbors[t][k]: the tet across local face k of tet t (the face opposite point k), -1 when
// the face belongs to t alone (a boundary face).
using TetNeighbors = std::vector<std::array<std::int32_t, 4>>;

// Faces by sorting 16-byte records (sorted point triple, 4 tet + k) and merging equal triples:
// 64 bytes a tet while it runs, freed on return. Throws InputError "<source>: tets[i]: ..." for
// a face shared by more than two tets, or by two tets on the same side of it (they overlap).
// So every face of a mesh that passes is shared by at most two tets, on opposite sides: the
// premise of the overlap check's boundary lemma (mesh_check.hpp). The side of a tet is the sign
// of the face plane n = (p1 - p0) x (p2 - p0) of the sorted points at the opposite point; the
// mesh has passed validate or repair (tet_mesh.hpp), so no tet is degenerate and the sign is
// well away from rounding (|6 V| > kDegenerateTetRatio x longest edge^3).
TetNeighbors tet_neighbors(const TetMesh& mesh, const std::string& source = "mesh");

// The local face of a tet opposite point k, as point slots of the tet.
inline constexpr std::array<std::array<int, 3>, 4> kTetFacePoints{{{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}}};

// The face plane of rule 1 (tet_traversal.hpp) of a sorted point triple: (p1 - p0) x (p2 - p0).
Vec3 face_plane(const TetMesh& mesh, const std::array<std::int32_t, 3>& sorted_points);

// The sorted point triple of local face k of tet t.
std::array<std::int32_t, 3> face_key(const TetMesh& mesh, std::size_t t, std::size_t k);

// face_key(mesh, t, k) for k = 0..3 at once: the tet's four indices are sorted once and face k
// is that order without (one copy of) point k, the same triples as four face_key calls.
std::array<std::array<std::int32_t, 3>, 4> face_keys(const TetMesh& mesh, std::size_t t);

}  // namespace rayint
