#pragma once
// VTK's quadratic volume cells -- quadratic tetra (VTK id 24, 10 nodes), quadratic hexahedron
// (25, 20 nodes), quadratic wedge (26, 15 nodes), quadratic pyramid (27, 13 nodes), triquadratic
// hexahedron (29, 27 nodes: gmsh's default order-2 hexahedron), biquadratic-quadratic wedge (32,
// 18 nodes: gmsh's default order-2 prism) -- in their own isoparametric interpolation,
// curved edges and faces included: x(p) = sum_i N_i(p) x_i, f(p) = sum_i N_i(p) f_i with VTK's
// quadratic shape functions (cells/quadratic_cells.hpp, checked against VTK 9.1). What
// cells/linear_cells.hpp does for the linear cells, for these: the inverse map, the faces as
// quadratic patches, ray-patch hits and the chord.
//
// Validity: a curved cell's map may fold (a mid-edge node pulled across the cell). make_quadratic_cell
// samples det J at the corners, the mid-edge nodes, the centre and a 5 x 5 x 5 lattice of the
// parametric domain (kJacobianSamples); det J must have one sign everywhere there and
// |det J| > kJacobianFloor = 1e-10 x extent^3 (the scale of a cell 1e-3 x thinner than its size
// is 1e-9; a fold crosses 0). Otherwise the cell is refused (std::invalid_argument saying where
// and what), since the interpolant is not a function of the point there. Both orientations are
// accepted (gmsh's prisms are VTK's mirrored, issue 29). This is a sampled test: a fold between
// the samples of a cell that is otherwise positive is not seen (it would need a cell bent by
// more than its own thickness between two lattice points 1/4 apart).
//
// Faces: the corners of face f are linear_face(corner type, f) (VTK's face tables, same index),
// the mid-edge nodes are the cell's nodes on those corner edges (VTK's edge lists of
// vtkQuadraticTetra, vtkQuadraticHexahedron, vtkQuadraticWedge, vtkQuadraticPyramid). A face is the trace of the cell
// map on it: a 6-node quadratic triangle (P2: corners A, B, C at (0,0), (1,0), (0,1) in (u, v),
// mid-edge nodes AB, BC, CA) or an 8-node serendipity quadrilateral (corners A, B, C, D at
// (0,0), (1,0), (1,1), (0,1), mid-edge nodes AB, BC, CD, DA). Two cells sharing a face see the
// same patch (the trace depends on the face's nodes only). The quadrilaterals of the 27-node
// hexahedron and of the 18-node wedge also have a face-centre node: their trace is the 9-node
// biquadratic Lagrange quadrilateral (the centre at (1/2, 1/2)), its triangles stay P2. The
// quadratic pyramid's base is the serendipity quadrilateral and its sides P2 triangles in the
// collapsed coordinates (quadratic_cells.hpp): the same patches. A pyramid is never affine.
//
// Ray-patch hits (intersect_quadratic_face): with e1, e2 orthonormal and perpendicular to the ray,
// the hits are the zeros of G(u, v) = (e1 . (P(u, v) - o), e2 . (P(u, v) - o)), a quadratic
// (triangle) or bi-quadratic (quadrilateral, serendipity or 9-node) map R^2 -> R^2 given by the
// projected nodes. Bracket:
// recursive subdivision of the face's domain (quadrilaterals into 4 rectangles, triangles into 4
// triangles), a sub-domain discarded when one component of G has all its Bernstein coefficients
// on that sub-domain (the patch lies in their convex hull) of one sign beyond kPatchExclusion =
// 1e-12 x the projected patch size; sub-domains alive at depth kPatchDepth = 5 (1/32 of the face)
// start Newton on G (2 x 2, at most 30 steps) from their centre. Roots within kFaceSlack
// (linear_cells.hpp) of the domain are kept, one per distinct (u, v) (closer than 1e-9: the same
// root reached from neighbouring sub-domains). t = (P - o) . d / |d|^2. Everything depends only on
// the nodes in the order given and on the ray: a shared face passed in canonical order
// (canonical_quadratic_face) gives both cells the same hits, bit for bit. Limitation: a ray
// tangent to a patch (a double root) may give one hit, two or none; the chord's midpoint test
// decides what is inside either way. A flat patch (every mid-edge node at its edge's midpoint
// within kAffineTolerance x magnitude, e.g. the interior faces of a curved gmsh mesh) is the
// corners' triangle or bilinear patch exactly and is intersected by intersect_face
// (linear_cells.hpp) instead: the decision depends on the nodes only, so both cells of a shared
// face take the same branch.
//
// Chord (quadratic_chord): as linear_cells.hpp's chord(): every face hit, sorted; an interval between
// consecutive distinct hits is inside when the inverse map of its midpoint converges into the
// domain (slack 1e-9), Newton started at the parametric point of the interval's first hit (the
// face point's reference coordinates), then the centre. The same Chord struct, so the traversal
// treats linear and quadratic cells alike.
//
// Inverse map: linear_cells.hpp's newton_inverse_map (kNewtonStepTolerance, kNewtonMaxIterations,
// kNewtonMaxStep; residual 8 eps x magnitude) with the shape functions and derivatives of
// quadratic_cells.hpp. Affine cells (every node at the affine image of its reference node within
// kAffineTolerance x magnitude, e.g. a straight-edged tet10) take the exact linear inverse
// instead: along a ray their scalar is a polynomial of degree <= 4 in t.
#include <array>
#include <cstdint>
#include <vector>

#include "rayint/cells/linear_cells.hpp"
#include "rayint/cells/quadratic_cells.hpp"
#include "rayint/geometry/vec3.hpp"

namespace rayint {

inline constexpr int kMaxQuadraticNodes = 27;
static_assert(kMaxQuadraticNodes <= kMaxNewtonNodes, "newton_inverse_map's buffers hold every quadratic cell");
inline constexpr int kJacobianSamples = 5;
inline constexpr double kJacobianFloor = 1e-10;
inline constexpr int kPatchDepth = 5;
inline constexpr double kPatchExclusion = 1e-12;

const char* quadratic_cell_name(QuadraticCellType type);        // VTK's names: "quadratic tetra", ...
LinearCellType quadratic_corner_type(QuadraticCellType type);   // tetra, hexahedron, wedge
int quadratic_face_count(QuadraticCellType type);                // 4, 6, 5

// Face f: corners (local node ids, cyclic, as linear_face of the corner type) and the mid-edge
// node of each corner edge: mid[k] lies on the edge (corner[k], corner[(k + 1) % count]); the
// face-centre node of a 9-node quadrilateral, -1 when the face has none.
struct QuadraticFaceNodes {
  std::array<int, 4> corner{};
  std::array<int, 4> mid{};
  int count = 0;  // 3 or 4 corners
  int centre = -1;
};

// A face patch's nodes: corners, mid-edge nodes, then the centre when there is one.
inline constexpr int kMaxPatchNodes = 9;
using PatchNodes = std::array<Vec3, kMaxPatchNodes>;
inline constexpr int patch_node_count(int corners, bool centre) { return 2 * corners + (centre ? 1 : 0); }
QuadraticFaceNodes quadratic_face(QuadraticCellType type, int face);

struct QuadraticCell {
  QuadraticCellType type = QuadraticCellType::hexahedron;
  std::array<Vec3, kMaxQuadraticNodes> x{};
  std::array<double, kMaxQuadraticNodes> value{};
  double extent = 0.0;       // largest corner-corner distance
  int orientation = 1;       // the sign of det J (one sign over the cell, make_quadratic_cell)
  bool affine = false;
  Eigen::Matrix3d affine_inverse = Eigen::Matrix3d::Identity();
  Vec3 affine_origin = Vec3::Zero();
};

// Throws std::invalid_argument for a wrong count, non-finite input, a cell of zero extent, or a
// map whose Jacobian determinant is not of one sign (see above), naming the parametric point.
QuadraticCell make_quadratic_cell(QuadraticCellType type, const std::vector<Vec3>& nodes,
                                  const std::vector<double>& values);

Vec3 quadratic_reference_centre(QuadraticCellType type);
Vec3 cell_position(const QuadraticCell& cell, const Vec3& p);
double cell_scalar(const QuadraticCell& cell, const Vec3& p);
Eigen::Matrix3d cell_jacobian(const QuadraticCell& cell, const Vec3& p);
InverseMap inverse_map(const QuadraticCell& cell, const Vec3& world, const Vec3& start);
InverseMap inverse_map(const QuadraticCell& cell, const Vec3& world);

// A face's nodes in canonical order: corners by canonical_face_order of their global ids (or
// coordinates), mid-edge nodes following their edges. node[0..count) corners, node[count + k]
// the mid-edge node of corner edge (k, k + 1), node[2 count] the centre when `centre`; `local`
// the cell's local ids in that order.
struct QuadraticFacePatch {
  PatchNodes node{};
  std::array<int, kMaxPatchNodes> local{};
  int count = 0;
  bool centre = false;
};
QuadraticFacePatch canonical_quadratic_face(const QuadraticCell& cell, int face,
                                            const std::int64_t* global_ids = nullptr);

// The patch point at (u, v) (triangle: barycentrics of corners 1 and 2).
Vec3 patch_point(const PatchNodes& node, int count, bool centre, double u, double v);

// A box holding the whole patch: the box of its Bernstein control points (the patch lies in
// their convex hull), for bounding-volume hierarchies.
void patch_control_box(const PatchNodes& node, int count, bool centre, Vec3& lo, Vec3& hi);

struct PatchHit {
  double t = 0.0;
  double u = 0.0, v = 0.0;
};
// Every hit of the line origin + t direction with the closed patch, sorted by t (see above).
std::vector<PatchHit> intersect_quadratic_face(const PatchNodes& node, int count, bool centre, const ViewRay& ray);

// The pieces of the line inside the cell (see above; the Chord of linear_cells.hpp).
Chord quadratic_chord(const QuadraticCell& cell, const ViewRay& ray, const std::int64_t* global_ids = nullptr);

}  // namespace rayint
