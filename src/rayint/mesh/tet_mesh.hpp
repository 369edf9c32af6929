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
#include <map>
#include <string>
#include <vector>

#include "rayint/geometry/vec3.hpp"

namespace rayint {

// One data array of a mesh file, as `rayint mesh info` lists it.
struct MeshArrayInfo {
  std::string name;
  std::string association;  // "point" or "cell"
  long components = 1;
  bool marker = false;      // a region marker / physical tag (is_marker_array): never the scalar
};

// What a reader found in the file beside the tets it kept (eval JSON "mesh_repairs", `render
// --stats`, `rayint mesh info`). Every reader fills it the same way (cells/cell_types.hpp).
struct MeshFileInfo {
  std::map<std::string, long> cells_by_type;    // every cell as read, by cell-type name
  std::map<std::string, long> skipped_by_type;  // dimension 0-2 cells dropped (vertex, line, ...)
  long skipped_cells = 0;                       // their total
  long ghost_cells = 0;                         // vtkGhostType duplicate cells dropped
  long merged_points = 0;                       // points of several pieces merged (equal coordinates)
  long skipped_node_data = 0;                   // gmsh $NodeData entries for no saved node (tag -1, or in MSH 4.1 past the last $Nodes tag)
  std::vector<long long> cell_ids;              // per tet: its cell index (gmsh: element tag) in the file
  std::vector<MeshArrayInfo> arrays;            // every data array of the file
  std::string scalar;                           // the array taken as the scalar ("" inline)
  std::string scalar_association = "point";     // "point" or "cell"
};

struct TetMesh {
  std::vector<Vec3> points;
  std::vector<double> scalars;                   // one per point (empty when cell_scalars is used)
  std::vector<std::array<std::int32_t, 4>> tets;  // point indices, VTK order
  // Cell data: one scalar per tet, constant over the tet (empty for point data). The scalar is
  // then piecewise constant along a ray, with a jump at faces between cells; traversal gives each
  // crossing s_in == s_out == the cell's value, so every integrator sees a constant segment and
  // the exact method is exact on it.
  std::vector<double> cell_scalars;
  // Quadratic tetrahedra (VTK_QUADRATIC_TETRA, gmsh order 2, tetgen -o2): per tet the point
  // indices of its six mid-edge nodes in VTK's edge order (cells/cell_types.hpp, kTet10Edges);
  // -1 for every edge of a linear tet of a mixed mesh (its mid-edge value is then the mean of
  // the edge's ends, which reproduces the linear field exactly). Empty when every tet is linear.
  // The corners stay in `tets`, so traversal walks a tet10 as the tetrahedron of its corners;
  // the scalar inside is quadratic (mesh/quadratic_tets.hpp). A mesh with curved edges goes to the own-cells path (mesh/cell_traversal.hpp).
  std::vector<std::array<std::int32_t, 6>> edge_nodes;
  MeshFileInfo info;
};

// True for arrays that label regions rather than carry a field: gmsh's physical and geometrical
// tags as meshio writes them ("gmsh:physical", "gmsh:geometrical", "gmsh:dim_tags"), meshio's
// other format tags ("medit:ref", "tetgen:ref", "flac3d:zone", "avsucd:material", "cell_tags",
// "point_tags"), VTK's bookkeeping (vtkGhostType, vtkOriginalPointIds, vtkOriginalCellIds,
// vtkProcessId) and the common names "region", "marker", "material_id", "subdomain". Matched
// case-sensitively, as written by those tools.
bool is_marker_array(const std::string& name);

// Point data as ParaView's Cell Data to Point Data filter derives it (vtkCellDataToPointData,
// default settings): the value at a point is the plain average of the values of the cells that
// use it. Points used by no tet get 0. Returns one value per point.
std::vector<double> cell_to_point_average(const TetMesh& mesh);

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
  long skipped_cells = 0;                       // dimension 0-2 cells the reader dropped
  std::map<std::string, long> skipped_by_type;  // by cell-type name
  long ghost_cells = 0;                         // vtkGhostType duplicate cells dropped
  long reoriented = 0;   // inverted, reordered (points 2 and 3 swapped)
  long zero_volume = 0;  // dropped: repeated point index or 6V == 0 exactly (own mode: zero-volume
                         // cells of any type, mesh/cell_mesh.hpp zero_volume_cell)
  std::map<std::string, long> zero_volume_by_type;  // own mode: the dropped cells by type name
  long slivers = 0;      // dropped: 0 < |6V| <= kDegenerateTetRatio l^3
  // `--cells split` (mesh/cell_split.hpp): the file's cells by type that were tetrahedralised as
  // VTK's vtkDataSetTriangleFilter does, an approximation; empty when the file was not split.
  std::map<std::string, long> split_cells;
};
// The shape of tet i (its indices must be in range).
TetShape classify_tet(const TetMesh& mesh, std::size_t tet);

// The smallest extent (box diagonal of the points) a mesh may have. Below it the squared face
// areas the traversal and the checks form (~extent^4) leave double's normal range (from ~1e-77)
// and tetrahedron volumes underflow (from ~1e-103): a mesh scaled to 1e-90 was refused as
// overlapping, one at 1e-150 as all zero-volume; every ray still gave its unscaled crossings down
// to 1e-80 through tetrahedra and 1e-75 through cells in their own interpolation (issue 33, round
// 20, tests/test_mesh_frames.cpp checks from this limit up).
inline constexpr double kMinMeshExtent = 1e-60;
// Throws InputError "<source>: <names.points>: ..." when the points' extent is positive but
// below kMinMeshExtent (scaling the mesh, and its densities by the inverse, is the remedy). A
// zero extent is left to the degeneracy checks. The points must be finite.
void check_mesh_extent(const std::vector<Vec3>& points, const std::string& source, const MeshFieldNames& names = {});

// Checks the structure only: at least one point and one tet, scalar count == point count, finite
// coordinates (spanning at least kMinMeshExtent) and scalars, indices in [0, points). Every reader calls this; orientation and
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
