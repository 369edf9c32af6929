#pragma once
// Generated tetrahedral meshes with analytic fields, for cases/ and tests: a structured box cut
// into tetrahedra, a ball, a square ring (non-convex: a hole through it), each with a field given
// as a function of position. `rayint generate-mesh` writes them (cases/meshes/*.vtk are its
// output; scripts/generate-meshes.sh regenerates them all).
//
// Every box cell is cut into the 6 tetrahedra of Kuhn's (Freudenthal's) subdivision around the
// diagonal (0,0,0)-(1,1,1), the same in every cell, so the mesh is conforming (neighbouring
// cells share whole faces). All tets are positively oriented (VTK's convention).
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "rayint/geometry/vec3.hpp"
#include "rayint/mesh/tet_mesh.hpp"

namespace rayint {

// (nx, ny, nz) cells over the box [lo, hi]; 6 nx ny nz tets, (nx+1)(ny+1)(nz+1) points.
TetMesh structured_box_mesh(const Vec3& lo, const Vec3& hi, int nx, int ny, int nz);

// Keeps the tets whose centroid satisfies `keep` and drops points no tet uses.
TetMesh keep_tets(const TetMesh& mesh, const std::function<bool(const Vec3&)>& keep);

// Sets scalar i = field(point i).
void assign_field(TetMesh& mesh, const std::function<double(const Vec3&)>& field);

// Moves every point not on the box boundary by a uniform random offset of up to `fraction` of
// the cell size per axis (seeded, reproducible), so cells are irregular.
void jitter_interior(TetMesh& mesh, const Vec3& lo, const Vec3& hi, int n, double fraction,
                     std::uint64_t seed);

// The kinds `rayint generate-mesh` knows; each describes itself in `description`.
struct GeneratedMesh {
  TetMesh mesh;
  std::string description;  // what it is, the field, and the command that made it
};
std::vector<std::string> generated_mesh_kinds();
// kind: "ball" (radius 1, s = 1 - |x|), "linear-box" (jittered [-1,1]^3, s = 0.5 + 0.3 x - 0.2 y
// + 0.4 z), "ring" (square ring [-1,1]^2 x [-0.25,0.25] minus the hole |x|,|y| < 0.4,
// s = sqrt(x^2 + y^2)). `n` cells per unit edge of the underlying grid. Throws
// std::invalid_argument for an unknown kind or n out of [1, 200].
GeneratedMesh generate_mesh(const std::string& kind, int n, std::uint64_t seed);

}  // namespace rayint
