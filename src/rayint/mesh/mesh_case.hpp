#pragma once
// A mesh case: transfer functions, a tetrahedral mesh with point scalars, and viewing rays given
// one by one or by a camera (format: cases/README.md, "Mesh cases"). Tracing its rays through the
// mesh gives an ordinary Case, so `rayint eval`, `check`, `bench` and `gate` take mesh cases
// unchanged.
#include <optional>
#include <string>
#include <vector>

#include "rayint/geometry/vec3.hpp"
#include "rayint/mesh/cell_split.hpp"
#include "rayint/mesh/surface_shading.hpp"
#include "rayint/mesh/tet_mesh.hpp"
#include "rayint/mesh/tet_traversal.hpp"
#include "rayint/model/ray.hpp"
#include "rayint/geometry/camera.hpp"

namespace rayint {

struct MeshViewRay {
  ViewRay ray;
  Rgb background{0.0, 0.0, 0.0};
};

struct MeshCase {
  std::string name, description, source;
  std::string mesh_source;  // the .vtk file, or `source` for an inline mesh
  TransferFunctions transfer;
  TetMesh mesh;
  // Face adjacency of `mesh` (mesh/tet_adjacency.hpp), computed on load for the overlap check;
  // hand it to the TetTraversal (moved, when the mesh is) so the faces are not sorted twice.
  TetNeighbors neighbors;
  TetRepairs repairs;             // what reading reoriented or dropped (all 0 under --strict-mesh)
  // `--cells split`: the file's cells were tetrahedralised as vtkDataSetTriangleFilter does (an
  // approximation of their own interpolation; mesh/cell_split.hpp). Every output says so.
  std::optional<CellSplitCounts> split;
  // The file holds cells other than tetrahedra and `--cells split` was not given: they are
  // integrated in their own interpolation (mesh/cell_traversal.hpp, "mode": "own"); `mesh` is
  // then empty.
  std::optional<CellMesh> cells;
  std::vector<MeshViewRay> rays;  // "rays" (may be empty when a camera is given)
  std::optional<Camera> camera;   // "camera"
  Rgb background{0.0, 0.0, 0.0};  // "background": behind every camera pixel
  SurfaceShading shading;         // "shading": off unless given
};

// The viewing rays `rayint eval` evaluates: "rays" when given, otherwise one per camera pixel
// (row-major, row 0 at the top).
std::vector<MeshViewRay> evaluation_rays(const MeshCase& mesh_case);

// The Case of `mesh_case`'s evaluation rays traced through `mesh` (built from mesh_case.mesh).
Case trace_mesh_case(const MeshCase& mesh_case, const TetTraversal& mesh, TraversalStats* stats = nullptr);

}  // namespace rayint
