#pragma once
// A mesh of linear tetrahedra with one scalar per point: what every mesh input (VTK legacy .vtk,
// inline JSON, and later .vtu) is read into, and what traversal (mesh/tet_traversal.hpp) walks.
//
// Orientation convention (VTK's): a tet (p0, p1, p2, p3) is positively oriented when
// (p1 - p0) x (p2 - p0) . (p3 - p0) > 0. Meshes arrive with either order (TetGen 1.6 and gmsh
// 4.8 write VTK's on the fixtures of tests/fixtures/meshes/, meshio keeps whatever order it is
// given, a Kuhn split written as its axis permutations come alternates), so by default a reader
// accepts them:
// repair_tet_mesh() reorients inverted tets and drops degenerate ones, and counts both
// (TetRepairs, reported by `rayint eval` and `render --stats`). validate_tet_mesh is the strict
// policy (`--strict-mesh`): it refuses inverted and degenerate tets with their index.
//
// Why reorienting changes nothing: the ray integral depends only on the set of points a cell
// covers and the linear field on it; swapping p2 and p3 changes neither (traversal builds each face
// from its sorted point indices, so the face planes are the same doubles; only the Eq. 9 fit sees
// the points in another order). Measured (tests/test_mesh_repair.cpp, "[mesh][repair]"): the
// jittered Kuhn box linear-box n = 3 with 972 of 1,296 tets written inverted, and reoriented,
// give intensities within 2.2e-16 over 3,000 rays (target 1e-14).
//
// Why dropping a degenerate tet costs (almost) nothing: a zero-volume tet covers no volume, so it
// has no length along any ray; its neighbours across it become boundary faces, and traversal
// re-enters the mesh on the far side (tet_traversal.hpp, rule 4), which is how gaps between
// components are already followed. A sliver (below) has a height h <= kDegenerateTetRatio l^3 /
// (2 A) over its largest face (area A, longest edge l); a ray crossing it at angle theta to that
// face loses at most h / sin(theta) of length.
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
// Names used in counts and messages: "zero volume" = a repeated point index or 6V == 0 exactly;
// "sliver" = 0 < |6V| <= kDegenerateTetRatio l^3 (l: longest edge). Both are degenerate.
inline constexpr double kDegenerateTetRatio = 1e-12;

enum class TetShape { Positive, Inverted, ZeroVolume, Sliver };

// What repair_tet_mesh did: counts of the tets as read.
struct TetRepairs {
  long tets_read = 0;
  long reoriented = 0;   // inverted, reordered (points 2 and 3 swapped)
  long zero_volume = 0;  // dropped: repeated point index or 6V == 0 exactly
  long slivers = 0;      // dropped: 0 < |6V| <= kDegenerateTetRatio l^3
};
// The shape of tet i (its indices must be in range).
TetShape classify_tet(const TetMesh& mesh, std::size_t tet);

// Checks the structure only: at least one point and one tet, scalar count == point count, finite
// coordinates and scalars, indices in [0, points). Every reader calls this; orientation and
// degeneracy are left to repair_tet_mesh (default) or validate_tet_mesh (strict).
void validate_tet_mesh_structure(const TetMesh& mesh, const std::string& source,
                                 const MeshFieldNames& names = {});

// Strict: validate_tet_mesh_structure, and also four distinct indices per tet, no degenerate and
// no inverted tet. Throws InputError "<source>: <field>[i]...: <what>" on the first problem.
void validate_tet_mesh(const TetMesh& mesh, const std::string& source,
                       const MeshFieldNames& names = {});

// Reorients inverted tets and removes degenerate ones (points are kept). The mesh must pass
// validate_tet_mesh_structure. Throws InputError "<source>: <names.tets>: ..." when no tet is
// left. tet i of the result is the i-th kept tet of the input.
TetRepairs repair_tet_mesh(TetMesh& mesh, const std::string& source, const MeshFieldNames& names = {});

// 6 x signed volume of tet i: (p1 - p0) x (p2 - p0) . (p3 - p0).
double signed_volume6(const TetMesh& mesh, std::size_t tet);

// Swaps points 2 and 3 of every tet with negative volume; returns how many were swapped.
std::size_t reorient_tets(TetMesh& mesh);

}  // namespace rayint
