#pragma once
// Rays through a mesh of linear VTK cells (mesh/cell_mesh.hpp: tetrahedra, voxels, hexahedra,
// wedges, pyramids, mixed) in the cells' OWN interpolation: the cells a viewing ray crosses, in
// order, each chord integrated by cells/cell_integral.hpp (LinearCellIntegrator: the scalar is the
// isoparametric interpolant, not a polynomial in t) and composited front to back. This is the
// default for files with cells other than tetrahedra ("mode": "own"); `--cells split` integrates
// VTK's tetrahedralisation instead (mesh/cell_split.hpp), and a file of tetrahedra only keeps the
// tetrahedral path (mesh/tet_traversal.hpp), unchanged.
//
// Faces and adjacency: every cell face is keyed by its sorted global point ids (3 for a triangle,
// 4 for a quadrilateral); two cells with the same key share the face (a quadrilateral shared by
// two cells is one bilinear patch), a key held once is a boundary face, more than twice is refused.
//
// Chords (cells/linear_cells.hpp: chord with the cell's global point ids): every face is
// intersected with its nodes in the canonical order of their global ids, so a face shared by two
// cells gives both the same hit parameters, bit for bit, and the exit of one cell is the entry
// of the next (watertight). The pieces of the ray inside a cell are the intervals between face
// hits whose midpoint maps (Newton) into the cell.
// Planar faces (cell_traversal.cpp, "Planar faces"): each distinct face is stored once; one
// planar to the rounding of its coordinates (twist term's normal part <= kAffineTolerance x its
// largest coordinate, strictly convex), and every triangle, is intersected as its plane by one
// routine for both cells (still bit for bit the same hit in both). An affine cell whose faces are
// all planar is the convex polyhedron of its face planes: its chord is [last entry, first exit]
// over them, without the hits' classification (no Newton). Other linear cells classify their
// hits as chord() does (classify_chord_intervals).
//
// Walk. Rules, as for tetrahedra (tet_traversal.hpp):
//  1. t never decreases. In a cell entered at t the ray is integrated over [t, t_far] with t_far
//     the end of the cell's chord interval that holds t (its start within kCellEntrySlack of t);
//     the next cell starts at t_far. Consecutive chords share their end points, so nothing is
//     lost or counted twice, whatever rounding does to an individual face hit.
//  2. The next cell is found among the cells across the faces hit at t_far (the face hit list of
//     the chord); when none of them continues the ray beyond t_far (an exit through an edge or a
//     vertex, into a cell that shares only that edge or vertex), among every cell that shares a
//     point with those faces; the one whose chord interval holding t_far reaches furthest wins.
//     (That star search skips a linear cell whose corner box, padded by 1e-7 x (mesh diagonal +
//     largest |coordinate|), misses the exit point by more than the slack below: its chord lies
//     in its corners' hull up to the face hits' slack, so it cannot hold t_far.)
//     A candidate "holds" t when its interval starts at or before t + kCellEntrySlack x the
//     length scale (mesh diagonal + |t|) and ends beyond t.
//  3. No cell continues the ray: it has left the mesh. The next entry is the nearest boundary
//     face hit beyond t whose cell holds that hit (first hit: Embree 3 user geometry over the
//     boundary faces, bounds = the face's node box (a bilinear patch lies in the convex hull of its
//     corners) padded by 1e-7 of the diagonal; every hit is computed in double by face_hits (the plane or intersect_face),
//     nodes in canonical order). So rays that leave and re-enter a non-convex mesh, and meshes of
//     several components, are followed to the end. Every re-entry is strictly beyond t.
//  4. A hard budget of 8 x cells + 1000 steps per ray; hitting it is counted.
// A chord whose midpoint classification did not converge (Newton) or whose integral failed marks
// the ray failed: counted, and the ray's value is not a result (CellRayResult::converged).
//
// Quadratic cells (tet10, hex20, wedge15: cells/quadratic_isoparametric.hpp), curved or not, take
// part in the same walk: their faces are keyed by their corners like the linear ones (the same
// face indices), a face is a quadratic patch through its corners and mid-edge nodes, intersected
// with the nodes in the canonical order of the corners' global ids (so a shared curved face is
// watertight as above), the chord is quadratic_chord, the integral LinearCellIntegrator's
// quadratic overload. cell(c) of a quadratic cell is its corners' linear cell (its faces'
// corners); quadratic_cell(c) the cell itself. A boundary patch's first-hit box is the box of
// its Bernstein control points (patch_control_box), padded as above. A quadratic cell whose map
// folds (det J of both signs or ~0, make_quadratic_cell) is refused naming it.
//
// The eye may be inside the mesh: the walk starts outside the bounding box (origin moved back
// along the ray) and the chords are clipped at the true origin, as tet_traversal does.
#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "rayint/cells/cell_integral.hpp"
#include "rayint/cells/linear_cells.hpp"
#include "rayint/cells/quadratic_isoparametric.hpp"
#include "rayint/core/counters.hpp"
#include "rayint/geometry/vec3.hpp"
#include "rayint/mesh/cell_mesh.hpp"
#include "rayint/model/transfer_function.hpp"

namespace rayint {

class CellBoundaryFirstHit;

// How far (x (mesh diagonal + |t|)) a candidate's chord may start beyond the current t and still
// be taken as continuing the ray: face hits computed from different faces through one edge or
// vertex differ by rounding (~1e-16 relative); 1e-10 leaves a wide margin and is far below any
// cell of a mesh whose diagonal is 1e6 x the cell.
inline constexpr double kCellEntrySlack = 1e-10;

// One cell's chord on a ray: [t_in, t_out] in the walk's parameters (CellTrace::origin + t d).
struct CellChordOnRay {
  std::int32_t cell = -1;
  double t_in = 0.0, t_out = 0.0;
  // The classification's parametric point in the chord (ChordInterval::p_mid): the integral's
  // first Newton start. NaN when none.
  Vec3 p_hint = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
};

struct CellTrace {
  Vec3 origin = Vec3::Zero();      // t = 0 of the chords
  Vec3 direction = Vec3::UnitZ();  // unit
  double t_eye = 0.0;              // the eye's parameter: chords are clipped there
  std::vector<CellChordOnRay> chords;  // near -> far, t_in < t_out, consecutive within the mesh
  long failed_chords = 0;          // cells whose chord classification did not converge
};

struct CellTraversalStats {
  long rays = 0;
  long chords = 0;
  long face_steps = 0;         // next cell found across a face hit at the exit
  long star_steps = 0;         // next cell found among the cells sharing a point (edge, vertex exit)
  long first_hit_queries = 0;  // entries and re-entries asked of the boundary structure
  long failed_chords = 0;
  long budget_exhausted = 0;
  void add(const CellTraversalStats& o);
};
// Every counter of CellTraversalStats (core/counters.hpp), in the shard format's order.
inline constexpr std::array<Counter<CellTraversalStats>, 7> kCellTraversalCounters{{
    {"rays", &CellTraversalStats::rays},
    {"chords", &CellTraversalStats::chords},
    {"face_steps", &CellTraversalStats::face_steps},
    {"star_steps", &CellTraversalStats::star_steps},
    {"first_hit_queries", &CellTraversalStats::first_hit_queries},
    {"failed_chords", &CellTraversalStats::failed_chords},
    {"budget_exhausted", &CellTraversalStats::budget_exhausted},
}};

// The integral of one ray: front-to-back composite of its chords, background behind.
struct CellRayResult {
  Rgb intensity{};      // emission + exp(-depth) background
  Rgb emission{};
  Rgb optical_depth{};
  double error_estimate = 0.0;  // sum of the chords' estimates (cell_integral.hpp)
  long chords = 0;
  long failed_chords = 0;       // chords not located or not integrated
  bool converged = true;        // false: intensity is not a result
  std::string failure;          // why (first failure)
};

class CellTraversal {
 public:
  // `mesh` must pass validate_cell_mesh_structure. Throws InputError "<source>: cells: ..." for a
  // face shared by more than two cells or a cell that make_linear_cell / make_quadratic_cell refuses.
  explicit CellTraversal(CellMesh mesh, const std::string& source = "mesh");
  ~CellTraversal();
  CellTraversal(const CellTraversal&) = delete;
  CellTraversal& operator=(const CellTraversal&) = delete;

  const CellMesh& mesh() const { return mesh_; }
  const LinearCell& cell(std::size_t c) const { return cells_[c]; }
  std::size_t cell_count() const { return cells_.size(); }
  // The quadratic cell c, or nullptr for a linear one.
  const QuadraticCell* quadratic_cell(std::size_t c) const {
    return quadratic_index_.empty() || quadratic_index_[c] < 0 ? nullptr
                                                               : &quadratic_[static_cast<std::size_t>(quadratic_index_[c])];
  }
  std::size_t face_count() const { return face_count_; }
  std::size_t boundary_face_count() const { return boundary_.size(); }
  // How many faces are planar (hit by their plane) and how many cells are chords by clipping
  // (affine, every face planar): "Planar faces" in cell_traversal.cpp.
  std::size_t planar_face_count() const;
  std::size_t clipped_cell_count() const { return static_cast<std::size_t>(std::count(clip_.begin(), clip_.end(), 1)); }
  const Vec3& box_min() const { return box_min_; }
  const Vec3& box_max() const { return box_max_; }
  // The global point ids of cell c, VTK order, as chord() takes them.
  std::array<std::int64_t, kMaxLinearNodes> global_ids(std::size_t c) const;

  // Every chord of the viewing ray (origin = eye; direction normalized here). Thread-safe.
  void trace(const ViewRay& ray, CellTrace& out, CellTraversalStats* stats = nullptr) const;
  // The chords of `trace` integrated in the cells' own interpolation and composited.
  CellRayResult integrate(const CellTrace& trace, const LinearCellIntegrator& integrator,
                          const Rgb& background) const;

  struct BoundaryFace {
    std::array<std::int32_t, 4> points{};  // canonical cyclic order (canonical_face_order)
    int count = 0;                          // 3 or 4
    std::int32_t cell = -1;
    int local = 0;  // face index in the cell (linear_face)
    std::array<std::int32_t, 4> mids{-1, -1, -1, -1};  // a quadratic face: mid-edge node of canonical
                                                       // corner edge (k, k + 1); -1 for a linear face
    std::int32_t centre = -1;  // a 9-node quadrilateral's face-centre node, else -1
    std::int32_t face = -1;    // its index among all faces (the linear faces' hits, face_hits)
  };
  const BoundaryFace& boundary_face(std::size_t i) const { return boundary_[i]; }

  struct Walk;  // one ray's walk state (cell_traversal.cpp; public only for the first-hit callbacks there)

 private:
  // The interval of cell c's chord that holds t (starts at or before t + slack, ends beyond t):
  // its end, and the faces hit there; false if none. Sets *failed when the chord failed.
  // `p_hint` gets the interval's ChordInterval::p_mid.
  bool continue_in(std::size_t c, const Walk& w, double t, double& t_far, std::vector<int>* exit_faces,
                   bool* failed, Vec3* p_hint = nullptr) const;
  bool next_cell(const Walk& w, std::size_t from, const std::vector<int>& exit_faces, double t,
                 std::int32_t& cell, double& t_far, std::vector<int>& faces, CellTraversalStats& stats,
                 bool& failed, Vec3& p_hint) const;
  friend struct CellFirstHitAccess;
  // The chord of linear cell c from its faces' shared geometry (faces_): clipped by the face planes
  // (clip_), or the face hits classified as chord() does. Same contract as continue_in.
  bool continue_in_linear(std::size_t c, const Walk& w, double t, double& t_far, std::vector<int>* exit_faces,
                          bool* failed, Vec3* p_hint) const;
  // The interval among `intervals` that holds t (rule 1), its end, p_mid and the faces hit there.
  static bool hold_interval(const ChordInterval* intervals, std::size_t n_intervals, const ChordFaceHit* hits,
                            std::size_t n_hits, const Walk& w, double t, double& t_far, std::vector<int>* exit_faces,
                            Vec3* p_hint);
  // The hits (ray parameters, sorted, at most 2) of the walk's line with face i of faces_.
  int face_hits(std::size_t i, const Walk& w, double* t) const;
  // The chord of cell c (linear or quadratic), nodes by their global ids (canonical faces).
  Chord cell_chord(std::size_t c, const ViewRay& ray) const;

  CellMesh mesh_;
  std::vector<LinearCell> cells_;
  std::vector<QuadraticCell> quadratic_;         // the quadratic cells
  std::vector<std::int32_t> quadratic_index_;    // per cell: its index in quadratic_, -1 if linear
                                                 // (empty when the mesh has no quadratic cell)
  std::vector<std::int32_t> neighbor_offsets_;  // cell c: neighbours_[neighbor_offsets_[c] + face]
  std::vector<std::int32_t> neighbors_;         // the cell across each face, -1 on the boundary
  std::vector<std::int32_t> point_cells_offsets_, point_cells_;  // cells around each point
  std::vector<BoundaryFace> boundary_;
  // Every distinct face of the linear cells, once (cell_traversal.cpp, "Planar faces"): its nodes
  // in canonical order and, when it is planar, its plane. Both cells of a shared face intersect
  // this one record, so they get the same hit parameters bit for bit (watertight).
  struct FaceGeometry {
    std::array<Vec3, 4> nodes{};
    Vec3 normal = Vec3::Zero();  // planar: normal . x = offset on the face
    double offset = 0.0;
    std::array<double, 4> edge_slack{};  // planar: the inside test's slack per edge
    int count = 0;
    bool planar = false;
  };
  static FaceGeometry planar_face_geometry(const std::array<Vec3, 4>& nodes, int count);
  std::vector<FaceGeometry> faces_;
  std::vector<std::int32_t> cell_faces_;  // neighbor_offsets_[c] + f: face f of cell c in faces_ (-1: quadratic cell)
  std::vector<std::int8_t> face_out_;     // neighbor_offsets_[c] + f: +1 when the face's normal points out of c, else -1
  std::vector<char> clip_;                // per cell: affine with every face planar: its chord is the planes' clip
  std::vector<std::array<double, 6>> cell_box_;  // per cell: its corners' box (min xyz, max xyz; quadratic: unbounded)
  double cell_box_pad_ = 0.0;             // next_cell's padding of cell_box_ (cell_traversal.cpp)
  std::size_t face_count_ = 0;
  Vec3 box_min_, box_max_;
  double diagonal_ = 0.0;
  std::unique_ptr<CellBoundaryFirstHit> first_hit_;
};

// The LinearCell of cell c of a CellMesh (points and scalars by VTK order; cell data: constant);
// for a quadratic type, its corners' linear type.
LinearCellType linear_type_of(MeshCellType type);

}  // namespace rayint
