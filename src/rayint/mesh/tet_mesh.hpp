#pragma once
// A mesh of linear tetrahedra with one scalar per point: what every mesh input (VTK legacy .vtk,
// inline JSON, and later .vtu) is read into, and what traversal (mesh/tet_traversal.hpp) walks.
//
// Orientation convention (VTK's): a tet (p0, p1, p2, p3) is positively oriented when
// (p1 - p0) x (p2 - p0) . (p3 - p0) > 0. validate_tet_mesh REJECTS inverted tets (negative
// volume) with their index rather than silently reordering them: an inverted tet in a mesh that
// is otherwise consistent is usually a bug upstream (wrong node order, a tangled element), and the
// user should see it. Use reorient_tets() first to accept meshes written with the opposite
// convention on purpose.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "rayint/geometry/vec3.hpp"

namespace rayint {

struct TetMesh {
  std::vector<Vec3> points;
  std::vector<double> scalars;                   // one per point
  std::vector<std::array<std::int32_t, 4>> tets;  // point indices, VTK order
};

// How the fields are called in the input, so errors name them as the user wrote them:
// inline JSON "mesh.points", "mesh.scalars", "mesh.tets"; VTK "POINTS", "POINT_DATA", "CELLS".
struct MeshFieldNames {
  std::string points = "points";
  std::string scalars = "scalars";
  std::string tets = "tets";
};

// A tet whose |6 V| is at most this times its longest edge cubed is degenerate (flat or with
// coincident points). A regular tet has 6V/l^3 = 0.118; 1e-12 still admits slivers that are
// eleven orders flatter, while the Eq. 9 solve on such a cell would lose ~12 digits.
inline constexpr double kDegenerateTetRatio = 1e-12;

// Checks: at least one point and one tet, scalar count == point count, finite coordinates and
// scalars, indices in [0, points), four distinct indices per tet, no degenerate and no inverted
// tet. Throws InputError "<source>: <field>[i]...: <what>" on the first problem.
void validate_tet_mesh(const TetMesh& mesh, const std::string& source,
                       const MeshFieldNames& names = {});

// 6 x signed volume of tet i: (p1 - p0) x (p2 - p0) . (p3 - p0).
double signed_volume6(const TetMesh& mesh, std::size_t tet);

// Swaps points 2 and 3 of every tet with negative volume; returns how many were swapped.
std::size_t reorient_tets(TetMesh& mesh);

}  // namespace rayint
