// The cell-type table (see cell_types.hpp).
#include "rayint/cells/cell_types.hpp"

#include <utility>
#include <vector>

namespace rayint {
namespace {

using S = CellSupport;

CellTypeInfo row(int vtk, const char* name, int nodes, int dim, int gmsh, std::vector<int> perm, S support,
                 std::optional<CellType> shape = std::nullopt) {
  CellTypeInfo r;
  r.vtk_id = vtk;
  r.name = name;
  r.nodes = nodes;
  r.dimension = dim;
  r.gmsh_id = gmsh;
  for (std::size_t i = 0; i < perm.size() && i < r.gmsh_to_vtk.size(); ++i) r.gmsh_to_vtk[i] = perm[i];
  r.support = support;
  r.shape = shape;
  return r;
}

std::vector<int> identity(int n) {
  std::vector<int> p(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) p[static_cast<std::size_t>(i)] = i;
  return p;
}

const std::vector<CellTypeInfo>& table() {
  static const std::vector<CellTypeInfo> rows = {
      // Dimension 0-2: skipped by every reader, counted.
      row(kVtkVertex, "vertex", 1, 0, 15, {0}, S::Skipped),
      row(2, "poly vertex", -1, 0, 0, {}, S::Skipped),
      row(kVtkLine, "line", 2, 1, 1, identity(2), S::Skipped),
      row(4, "poly line", -1, 1, 0, {}, S::Skipped),
      row(kVtkTriangle, "triangle", 3, 2, 2, identity(3), S::Skipped),
      row(6, "triangle strip", -1, 2, 0, {}, S::Skipped),
      row(7, "polygon", -1, 2, 0, {}, S::Skipped),
      row(8, "pixel", 4, 2, 0, {}, S::Skipped),
      row(kVtkQuad, "quad", 4, 2, 3, identity(4), S::Skipped),
      row(21, "quadratic edge", 3, 1, 8, identity(3), S::Skipped),
      row(22, "quadratic triangle", 6, 2, 9, identity(6), S::Skipped),
      row(23, "quadratic quad", 8, 2, 16, identity(8), S::Skipped),
      row(28, "biquadratic quad", 9, 2, 10, identity(9), S::Skipped),
      // Volume cells.
      row(kVtkTetra, "tetra", 4, 3, 4, identity(4), S::Traversed),
      row(kVtkQuadraticTetra, "quadratic tetra", 10, 3, 11, {0, 1, 2, 3, 4, 5, 6, 7, 9, 8}, S::Quadratic,
          CellType::tet10),
      // Linear cells other than the tetrahedron. gmsh's node numbering of the 8-node hexahedron,
      // 6-node prism and 5-node pyramid lists the nodes as VTK does (bottom face, then top face /
      // apex), so the permutations are the identity; checked on files gmsh 4.8 writes
      // (tests/test_cell_mesh.cpp, "[cellmesh]": every cell's faces are planar or bilinear quads
      // through its own nodes, and every interior face is shared by exactly two cells). gmsh's
      // prism (0, 1, 2) is counter-clockwise seen from (3, 4, 5), VTK's wedge (vtkWedge.h) is
      // clockwise: same nodes, opposite Jacobian sign. Both are accepted as written (the
      // interpolant does not depend on the sign, and a node is never separated from its scalar).
      row(kVtkVoxel, "voxel", 8, 3, 0, {}, S::CellPath),
      row(kVtkHexahedron, "hexahedron", 8, 3, 5, identity(8), S::CellPath, CellType::hex8),
      row(kVtkWedge, "wedge", 6, 3, 6, identity(6), S::CellPath),
      row(kVtkPyramid, "pyramid", 5, 3, 7, identity(5), S::CellPath),
      row(15, "pentagonal prism", 10, 3, 0, {}, S::NotYet),
      row(16, "hexagonal prism", 12, 3, 0, {}, S::NotYet),
      // gmsh 20-node hexahedron: edge nodes (0,1) (0,3) (0,4) (1,2) (1,5) (2,3) (2,6) (3,7) (4,5)
      // (4,7) (5,6) (6,7); VTK's: (0,1) (1,2) (2,3) (3,0) (4,5) (5,6) (6,7) (7,4) (0,4) (1,5) (2,6) (3,7).
      row(25, "quadratic hexahedron", 20, 3, 17,
          {0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15}, S::Isoparametric, CellType::hex20),
      // gmsh 15-node prism: edge nodes (0,1) (0,2) (0,3) (1,2) (1,4) (2,5) (3,4) (3,5) (4,5); VTK's:
      // (0,1) (1,2) (2,0) (3,4) (4,5) (5,3) (0,3) (1,4) (2,5).
      row(26, "quadratic wedge", 15, 3, 18, {0, 1, 2, 3, 4, 5, 6, 9, 7, 12, 14, 13, 8, 10, 11}, S::Isoparametric),
      // gmsh 13-node pyramid (gmsh type 19, Mesh.SecondOrderIncomplete = 1): edge nodes (0,1) (0,3)
      // (0,4) (1,2) (1,4) (2,3) (2,4) (3,4); VTK's (vtkQuadraticPyramid.h): (0,1) (1,2) (2,3) (3,0)
      // (0,4) (1,4) (2,4) (3,4). Checked on files gmsh 4.8 writes (tests [quadratic][pyramid]:
      // the .msh through this row equals gmsh's own .vtk, every edge node at its edge).
      row(27, "quadratic pyramid", 13, 3, 19, {0, 1, 2, 3, 4, 5, 8, 10, 6, 7, 9, 11, 12}, S::Isoparametric),
      // gmsh's order-2 hexahedron is this 27-node one unless Mesh.SecondOrderIncomplete = 1 (then
      // the 20-node one above); its prism is the 18-node one (gmsh type 13, VTK's biquadratic-
      // quadratic wedge 32) unless the same option gives the 15-node one.
      // gmsh 27-node hexahedron: the 20 nodes as the 20-node one, then the face centres of
      // (0,1,2,3) (0,1,4,5) (0,3,4,7) (1,2,5,6) (2,3,6,7) (4,5,6,7), then the cell centre; VTK's
      // (vtkTriQuadraticHexahedron.h): faces (0,4,7,3) (1,2,6,5) (0,1,5,4) (3,7,6,2) (0,3,2,1)
      // (4,5,6,7), then the centre.
      row(29, "triquadratic hexahedron", 27, 3, 12,
          {0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15, 22, 23, 21, 24, 20, 25, 26},
          S::Isoparametric),
      // gmsh 18-node prism: the 15 nodes as the 15-node one, then the centres of the quadrilaterals
      // (0,1,4,3) (0,2,5,3) (1,2,5,4); VTK's (vtkBiQuadraticQuadraticWedge.h): (0,1,4,3) (1,2,5,4) (2,0,3,5).
      row(32, "biquadratic-quadratic wedge", 18, 3, 13,
          {0, 1, 2, 3, 4, 5, 6, 9, 7, 12, 14, 13, 8, 10, 11, 15, 17, 16}, S::Isoparametric),
      row(42, "polyhedron", -1, 3, 0, {}, S::NotYet),
  };
  return rows;
}

}  // namespace

const CellTypeInfo* cell_type_from_vtk(long long vtk_id) {
  for (const CellTypeInfo& r : table())
    if (r.vtk_id == vtk_id) return &r;
  return nullptr;
}

const CellTypeInfo* cell_type_from_gmsh(long long gmsh_id) {
  if (gmsh_id <= 0) return nullptr;
  for (const CellTypeInfo& r : table())
    if (r.gmsh_id == gmsh_id) return &r;
  return nullptr;
}

std::string cell_type_label(long long vtk_id) {
  const CellTypeInfo* r = cell_type_from_vtk(vtk_id);
  return r != nullptr ? r->name : "VTK id " + std::to_string(vtk_id);
}

// The VTK cell types outside the table (vtkCellType.h, VTK 9.1; ids checked against python3-vtk9's
// VTK_* constants), named in refusals so that a user sees which cell the file holds.
const char* other_vtk_cell_name(long long vtk_id) {
  static const std::pair<int, const char*> names[] = {
      {0, "empty cell"}, {30, "quadratic-linear quad"}, {31, "quadratic-linear wedge"},
{33, "biquadratic-quadratic hexahedron"}, {34, "biquadratic triangle"},
      {35, "cubic line"}, {36, "quadratic polygon"}, {37, "triquadratic pyramid"}, {41, "convex point set"},
      {51, "parametric curve"}, {52, "parametric surface"}, {53, "parametric tri surface"},
      {54, "parametric quad surface"}, {55, "parametric tetra region"}, {56, "parametric hex region"},
      {60, "higher-order edge"}, {61, "higher-order triangle"}, {62, "higher-order quad"},
      {63, "higher-order polygon"}, {64, "higher-order tetrahedron"}, {65, "higher-order wedge"},
      {66, "higher-order pyramid"}, {67, "higher-order hexahedron"}, {68, "Lagrange curve"},
      {69, "Lagrange triangle"}, {70, "Lagrange quadrilateral"}, {71, "Lagrange tetrahedron"},
      {72, "Lagrange hexahedron"}, {73, "Lagrange wedge"}, {74, "Lagrange pyramid"}, {75, "Bezier curve"},
      {76, "Bezier triangle"}, {77, "Bezier quadrilateral"}, {78, "Bezier tetrahedron"},
      {79, "Bezier hexahedron"}, {80, "Bezier wedge"}, {81, "Bezier pyramid"}};
  for (const auto& [id, name] : names)
    if (id == vtk_id) return name;
  return nullptr;
}

std::string quadratic_split_message(long long vtk_id) {
  return "--cells split: " + cell_type_label(vtk_id) + " (VTK id " + std::to_string(vtk_id) +
         "): VTK's vtkDataSetTriangleFilter splits quadratic cells into linear tetrahedra on all their nodes in a way "
         "that depends on point ids and positions, which rayint does not reproduce; integrate this file without "
         "--cells split (its own isoparametric interpolation)";
}

std::string unsupported_cell_message(long long vtk_id) {
  const CellTypeInfo* r = cell_type_from_vtk(vtk_id);
  if (r == nullptr) {
    if (const char* name = other_vtk_cell_name(vtk_id))
      return std::string("cell type ") + name + " (VTK id " + std::to_string(vtk_id) +
             ") is not supported; VTK ids 10-14, 24-27, 29 and 32 are integrated";
    return "cell type " + std::to_string(vtk_id) + " is not a VTK cell type";
  }
  if (r->support == CellSupport::CellPath)
    return std::string("cell type ") + r->name + " (VTK id " + std::to_string(vtk_id) +
           "): the tetrahedral path integrates only tetrahedra; integrate this file with --cells split "
           "(VTK's tetrahedralisation, an approximation of the cell's own interpolation)";
  if (r->support == CellSupport::Isoparametric)
    return std::string("cell type ") + r->name + " (VTK id " + std::to_string(vtk_id) +
           "): the tetrahedral paths and --cells split take linear cells only; `rayint render` integrates it "
           "in its own (isoparametric) interpolation without --cells split";
  if (r->support == CellSupport::Quadratic)
    return std::string("cell type ") + r->name + " (VTK id " + std::to_string(vtk_id) +
           "): --cells split tetrahedralises linear cells only; read this file without --cells split "
           "(its straight-edged quadratic tetrahedra are integrated with their quadratic interpolation)";
  return std::string("cell type ") + r->name + " (VTK id " + std::to_string(vtk_id) +
         ") is not supported yet; tetrahedra, voxels, hexahedra, wedges, pyramids, quadratic tetrahedra, "
         "hexahedra, wedges and pyramids, triquadratic hexahedra and biquadratic-quadratic wedges (VTK ids 10-14, "
         "24-27, 29, 32) are integrated";
}

}  // namespace rayint
