#pragma once
// Rays through a tetrahedral mesh: the cells a viewing ray crosses, in order, with the scalar at
// each entry and exit (Williams & Max 1992, Eq. 9 and Eq. 13), and the resulting `Ray` of
// segments (far -> near) that every integrator takes unchanged.
//
// Traversal: the first boundary face is found with Embree (mesh/first_hit.hpp); from there the
// ray walks from cell to face-adjacent cell, leaving each cell through the face with the smallest
// crossing parameter. When it leaves through a boundary face it asks for the next entering face
// beyond that point, so non-convex meshes (the ray leaves and re-enters) and meshes with gaps
// (several components) are followed to the end.
//
// Robustness (rays through vertices, along edges, grazing faces). Four rules:
//  1. One plane per face. Every face is stored once, with one normal computed from its sorted
//     point indices; the crossing parameter t_f = n.(a - o)/(n.d) is computed from that plane by
//     whichever cell asks, so the exit parameter of one cell and the entry parameter of its
//     neighbour are the same double, and the sign of n.d says which of the two cells the ray
//     leaves. A face can therefore be crossed only in one direction: no back-and-forth.
//  2. t never decreases: a cell is left at max(t_in, min t_f). Segment lengths are differences of
//     consecutive parameters, so they sum to (last exit - first entry) minus the gaps: rounding
//     can move a face crossing by an ulp but cannot lose or double-count length.
//  3. Ties (the ray leaves a cell through an edge or a vertex, so several faces share the minimum
//     t_f) may lead into a cell the ray only touches: a zero-length step, which adds no segment.
//     After kZeroStepBudget such steps in a row, and at every exit through a boundary face, a
//     star search collects the cells around the current point p (breadth-first over face
//     neighbours whose closure holds p to within kStarTolerance x the mesh diagonal) and
//     continues in the one whose clipped ray interval starts at or before p and reaches furthest;
//     if none reaches beyond p, the ray has left the mesh there.
//  4. Re-entry queries accept only entering faces with t_f >= the current t minus
//     kStarTolerance x (diagonal + |t|) (computed in double from rule 1's planes, inside Embree's
//     filter); the entered cell starts at max(t, t_f) (rule 2), so the slack loses and doubles
//     nothing. It is there for two faces that meet across a dropped degenerate tet (tet_mesh.hpp:
//     repair_tet_mesh): the ray leaves one at t and enters the other at a t_f that rounding (or
//     a sliver thinner than the slack) puts just before t; without it the rest of the ray would
//     be lost. After a re-entry that made no progress the bound becomes strict (> t), so every
//     loop strictly advances t. A hard budget of 8 x cells + 1000 steps per ray is a last
//     resort; hitting it is counted (never silent).
// Tests (tests/test_mesh_traversal.cpp, [mesh]): rays exactly through vertices, along edges and
// along faces of a structured mesh give the analytic chord length to 1e-14 relative; non-convex
// and two-component meshes give the analytic in-mesh length. tests/test_mesh_repair.cpp
// ([mesh][repair]): a dropped zero-volume tet and a dropped sliver between two halves of a
// double pyramid, rays on a grid that includes its edges: analytic chord, nothing lost.
//
// The eye may be inside the mesh: the walk starts outside the bounding box (origin moved back
// along the ray) and the crossings are clipped at the true origin.
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "rayint/core/counters.hpp"
#include "rayint/core/prefaulted.hpp"
#include "rayint/geometry/bounds.hpp"
#include "rayint/geometry/vec3.hpp"
#include "rayint/mesh/tet_adjacency.hpp"
#include "rayint/mesh/quadratic_tets.hpp"
#include "rayint/mesh/tet_cell.hpp"
#include "rayint/mesh/tet_mesh.hpp"
#include "rayint/model/ray.hpp"

namespace rayint {

class BoundaryFirstHit;

inline constexpr int kZeroStepBudget = 4;
inline constexpr double kStarTolerance = 1e-10;

// One cell crossed by a ray: parameters relative to RayTrace::origin (increasing toward the far
// end) and the scalar there (Eq. 13: s(t) = v + w (t - t_in), v = s_in, w = gradient . d).
// In a mesh with quadratic tetrahedra (TetTraversal::quadratic()) the scalar is
// s(t) = s_in + w (t - t_in) + q (t - t_in)^2 (mesh/quadratic_tets.hpp); q is 0 otherwise.
struct CellCrossing {
  std::int32_t cell = -1;
  double t_in = 0.0, t_out = 0.0;
  double s_in = 0.0, s_out = 0.0;
  double q = 0.0;
};

struct RayTrace {
  Vec3 origin = Vec3::Zero();     // where t = 0 for the crossings (on the viewing ray)
  Vec3 direction = Vec3::UnitZ(); // unit
  double t_eye = 0.0;             // the eye's parameter; crossings start at or after it
  std::vector<CellCrossing> crossings;  // near -> far, non-overlapping, each t_out > t_in
};

struct TraversalStats {
  long rays = 0;
  long crossings = 0;          // segments produced
  long face_steps = 0;         // cell-to-cell steps
  long zero_length_steps = 0;  // steps through an edge or vertex that touched a cell
  long star_searches = 0;
  long first_hit_queries = 0;  // Embree queries (first entry and re-entries)
  long budget_exhausted = 0;   // rays cut short by the hard step budget (should stay 0)
  void add(const TraversalStats& o);
};
// Every counter of TraversalStats (core/counters.hpp), in the shard format's order.
inline constexpr std::array<Counter<TraversalStats>, 7> kTraversalCounters{{
    {"rays", &TraversalStats::rays},
    {"crossings", &TraversalStats::crossings},
    {"face_steps", &TraversalStats::face_steps},
    {"zero_length_steps", &TraversalStats::zero_length_steps},
    {"star_searches", &TraversalStats::star_searches},
    {"first_hit_queries", &TraversalStats::first_hit_queries},
    {"budget_exhausted", &TraversalStats::budget_exhausted},
}};

class TetTraversal {
 public:
  // `mesh` must pass validate_tet_mesh. Builds faces, face adjacency, Eq. 9 per cell and the
  // boundary first-hit structure. Throws InputError "<source>: tets: ..." for a face shared by
  // more than two tets or two tets overlapping across a face.
  explicit TetTraversal(TetMesh mesh, const std::string& source = "mesh");
  // The same with the mesh's face adjacency given (tet_neighbors(mesh), as the mesh case reader
  // computed it for the overlap check; moved in and freed once used): the faces are not sorted a
  // second time. An empty `neighbors` is computed here.
  TetTraversal(TetMesh mesh, TetNeighbors neighbors, const std::string& source);
  ~TetTraversal();
  TetTraversal(const TetTraversal&) = delete;
  TetTraversal& operator=(const TetTraversal&) = delete;

  const TetMesh& mesh() const { return mesh_; }
  // Eq. 9 of a cell: its gradient as stored, its anchor (the cell's point 0) and that point's
  // scalar (or the cell's) from the mesh: the values fit_linear_tet gave, bit for bit.
  LinearTetField field(std::size_t cell) const;
  const Vec3& gradient(std::size_t cell) const { return gradients_[cell]; }
  // True when the mesh has quadratic tetrahedra (TetMesh::edge_nodes with point scalars): the
  // crossings then carry the quadratic scalar, integrate them with QuadraticTraceIntegrator
  // (ray_from_trace refuses them).
  bool quadratic() const { return !quadratic_.empty(); }
  std::size_t cell_count() const { return mesh_.tets.size(); }
  std::size_t face_count() const { return face_count_; }
  std::size_t boundary_face_count() const { return boundary_.size(); }
  // The cell across local face k (opposite point k) of `cell`, or -1 on the boundary.
  std::int32_t neighbor(std::size_t cell, int k) const;
  const Vec3& box_min() const { return box_min_; }
  const Vec3& box_max() const { return box_max_; }

  // Every crossing of the viewing ray (origin = eye, direction normalized here). Thread-safe.
  void trace(const ViewRay& ray, RayTrace& out, TraversalStats* stats = nullptr) const;
  // The same for n rays: out[i] is trace(rays[i]), except that the rays' boundary queries (the
  // first entry, and the re-entry asked after each exit) go to Embree as packets of 8 (a render's
  // tile of neighbouring pixels: coherent rays), each lane with its own filter; Embree's packet
  // and single-ray kernels are the same watertight test, so the face found is trace()'s up to a
  // tie between faces hit at the same single-precision t (issue 33, round 12: renders
  // cmp-identical on the scaling meshes and the mesh cases).
  void trace_many(const ViewRay* rays, std::size_t n, RayTrace* out, TraversalStats* stats = nullptr) const;
  // What a render of linear segments needs: out[i] is ray_from_trace(trace(rays[i]), background)
  // (with Ray::quadratic cleared), the same doubles, but the walk writes each segment as it
  // crosses the cell (near -> far, into a per-thread buffer) and copies them into the Ray
  // reversed at the end, with no RayTrace in between (issue 33, rounds 20-21). The boundary queries go in packets as in trace_many. Throws
  // std::invalid_argument for a mesh with quadratic tets (as ray_from_trace does for their
  // crossings).
  void rays_many(const ViewRay* rays, std::size_t n, const Rgb& background, Ray* out,
                 TraversalStats* stats = nullptr) const;

  struct Face {
    std::array<std::int32_t, 3> points{};  // sorted ascending
    Vec3 normal = Vec3::Zero();            // (p1 - p0) x (p2 - p0) of the sorted points
    std::array<std::int32_t, 2> cells{-1, -1};
  };
  // Boundary face i (0 <= i < boundary_face_count(), in Embree's primitive order); cells[1] == -1.
  const Face& boundary_face(std::size_t i) const { return boundary_[i]; }

 private:
  struct Walk;
  // What one walk step needs about a cell, in one 128-byte record (2 cache lines) so that a step
  // does not gather from a face array, the signs and the fields (measured: the walk took ~30%
  // less time than with those separate arrays; README "Rendering throughput"). The values are
  // those of the face planes of rule 1, unchanged: normal k is face k's normal times the cell's
  // sign (+-1, an exact negation), so normal k . d = sign * (n.d) and
  // normal k . (a - o) / normal k . d = n.(a - o) / n.d bit for bit. A face's first point (its
  // lowest point index) is the cell's lowest-index point, except for the face opposite that point,
  // whose first point is the cell's second-lowest: both are kept as point indices (issue 33: the
  // record was 256 bytes with the two points and the Eq. 9 field in it; the field's gradient is
  // now in gradients_, its anchor and scalar in the mesh). Renders are cmp-identical to the
  // 256-byte records (reports/scaling/README.md, "Memory"). The normals are stored by component
  // (nx[k], ny[k], nz[k]), so that a step computes the faces' crossing parameters two (SSE2) or four
  // (AVX2) per instruction (issue 33, rounds 6 and 13); the arithmetic is Eigen's dot, (x0 y0 + x1 y1) + x2 y2
  // (dot3 below), lane by lane. The last 4 bytes hold the cell's point 0 (Eq. 9's anchor), so that
  // a crossing's scalar does not first load the cell's row of mesh_.tets (issue 33, round 20).
  struct alignas(64) CellRecord {
    alignas(16) std::array<double, 4> nx, ny, nz;  // face opposite point k, times the cell's sign (outward)
    std::array<std::int32_t, 4> next{};    // the cell across face k, -1 on the boundary
    std::int32_t first_point = 0;          // point index: the first point of every face but k_second
    std::int32_t second_point = 0;         // point index: the first point of face k_second
    std::int32_t k_second = -1;
    std::int32_t anchor = 0;               // point index: the cell's point 0, Eq. 9's anchor (field())
    Vec3 normal(int k) const {
      const auto i = static_cast<std::size_t>(k);
      return Vec3(nx[i], ny[i], nz[i]);
    }
  };
  static_assert(sizeof(CellRecord) == 128, "two cache lines per cell");
  // a . b in the order of Eigen's Vector3d dot with SSE2, (a0 b0 + a1 b1) + a2 b2 (compared bit for bit
  // on 2M random vectors when written; renders are cmp-identical to the Eigen-dot walk).
  static double dot3(const Vec3& a, const Vec3& b) { return (a[0] * b[0] + a[1] * b[1]) + a[2] * b[2]; }
  const Vec3& face_point(const CellRecord& r, int k) const {
    return mesh_.points[static_cast<std::size_t>(k == r.k_second ? r.second_point : r.first_point)];
  }
  // Rule 1: the crossing parameter of local face k of `cell`, the same double whichever cell asks.
  double crossing(const Walk& w, std::size_t cell, int k) const;
  bool star_search(const Walk& w, std::int32_t from, double t, std::int32_t& cell, double& t_out) const;
  // trace() in steps, so that trace_many can ask several rays' boundary queries at once:
  // walk_begin from the ray's start (mesh_walk_start); while walk_query says a boundary query is
  // due (its t_near; the rest is in the state), walk_on from its answer (-1: none, the ray is
  // done); walk_end adds the counts.
  struct WalkState;
  void walk_begin(const MeshWalkStart& start, RayTrace* out, Ray* ray, WalkState& s) const;
  bool walk_query(WalkState& s, double& t_near) const;
  void walk_on(WalkState& s, std::int64_t prim) const;
  void walk_end(WalkState& s, TraversalStats* stats) const;
  // trace_many and rays_many: one of `out` (crossings) and `ray_out` (segments) is given.
  void walk_many(const ViewRay* rays, std::size_t n, RayTrace* out, Ray* ray_out, TraversalStats* stats) const;
  friend struct FirstHitFilterAccess;

  TetMesh mesh_;
  // cells_ and gradients_ are written in full by the constructor: prefaulted, and from 2 MiB in
  // transparent huge pages (core/prefaulted.hpp; 13.5 + 2.5 MB at 105k tets, NOTES rounds 15-16).
  std::vector<CellRecord, PrefaultedAllocator<CellRecord>> cells_;
  std::vector<Vec3, PrefaultedAllocator<Vec3>> gradients_;  // Eq. 9 gradient per cell (24 B; used once per crossing)
  std::vector<Face> boundary_;            // boundary faces, in Embree's primitive order
  std::vector<std::int8_t> boundary_k_;   // local index of boundary_[i] in boundary_[i].cells[0]
  std::size_t face_count_ = 0;
  Vec3 box_min_, box_max_;
  double diagonal_ = 0.0;
  std::unique_ptr<BoundaryFirstHit> first_hit_;
  std::vector<QuadraticTetField> quadratic_;  // per cell, only for a mesh with quadratic tets
};

// The Ray the integrators take: one segment per crossing, ordered far -> near, with the
// background entering at the far end. A ray that misses the mesh has no segments (only the
// background reaches the eye). Throws std::invalid_argument for a quadratic crossing (q != 0):
// a linear segment would be another field (use poly_ray_from_trace, mesh/quadratic_tets.hpp).
Ray ray_from_trace(const RayTrace& trace, const Rgb& background);
// The same into `out`, reusing its storage (no allocation per ray in a render loop).
void ray_from_trace(const RayTrace& trace, const Rgb& background, Ray& out);
// The same with quadratic crossings kept: Ray::quadratic holds each crossing's q (model/ray.hpp;
// the scalar s(t) = s_in + w (t - t_in) + q (t - t_in)^2 keeps its coefficient q of the squared
// distance from either end), so the methods that take quadratic chords integrate the quadratic
// scalar and the others refuse the ray (integrators/integrator.hpp). A linear trace gives the
// Ray of ray_from_trace, with Ray::quadratic empty.
Ray ray_with_quadratic_chords(const RayTrace& trace, const Rgb& background);
Ray mesh_ray(const TetTraversal& mesh, const ViewRay& ray, const Rgb& background,
             TraversalStats* stats = nullptr);

}  // namespace rayint
