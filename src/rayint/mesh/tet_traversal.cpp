// Ray traversal of a tetrahedral mesh (see tet_traversal.hpp for the method and its robustness
// rules, numbered 1-4 below as there).
#include "rayint/mesh/tet_traversal.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "rayint/core/error.hpp"
#include "rayint/core/lanes.hpp"
#include "rayint/geometry/bounds.hpp"
#include "rayint/core/format.hpp"
#include "rayint/mesh/first_hit.hpp"
#include "rayint/mesh/tet_adjacency.hpp"

namespace rayint {

void TraversalStats::add(const TraversalStats& o) {
  add_counters(*this, o, kTraversalCounters);
}

namespace {
// The largest point coordinate taken. It was Embree's range: Embree works in single precision and
// asserts ray.valid(): |origin|, |direction| <= FLT_LARGE = 1.844e18 (embree
// common/math/constants.h), and a point at 4e252 aborted the process (found by fuzz/gmsh_fuzzer and
// fuzz/vtk_legacy_fuzzer; tests/test_fuzz_regressions.cpp). Since Embree's copy lives in a
// LocalFrame (mesh/embree_ray.hpp: box centre, unit size) it sees no coordinate beyond a few
// units, so the bound is now the walk's, and conservative: face normals (~size^2) and plane
// products (~size^3) stay far from overflow at 1e18, and the frames are tested to 1e17
// (tests/test_mesh_frames.cpp); beyond it nothing is tested, so it stays refused.
constexpr double kMaxCoordinate = 1e18;

// Eq. 9 of a cell: its gradient as stored, its anchor point p0 (the cell's point 0) and that
// point's scalar, or the cell's own scalar for cell data. Shared by field() and the walk's
// crossings (inlined into the walk's AVX2 copy too).
[[gnu::always_inline]] inline LinearTetField cell_field(const TetMesh& mesh, const Vec3& gradient, std::size_t cell,
                                                        std::size_t p0) {
  LinearTetField f;
  f.anchor = mesh.points[p0];
  f.anchor_scalar = mesh.cell_scalars.empty() ? mesh.scalars[p0] : mesh.cell_scalars[cell];
  f.gradient = gradient;
  return f;
}

// The four faces at a time in the walk: core/lanes.hpp.
using lanes::M4;
using lanes::V4;
}  // namespace

TetTraversal::TetTraversal(TetMesh mesh, const std::string& source)
    : TetTraversal(std::move(mesh), TetNeighbors{}, source) {}

TetTraversal::TetTraversal(TetMesh mesh, TetNeighbors neighbors, const std::string& source) : mesh_(std::move(mesh)) {
  for (std::size_t i = 0; i < mesh_.points.size(); ++i)
    for (int k = 0; k < 3; ++k)
      if (!(std::fabs(mesh_.points[i][k]) <= kMaxCoordinate))
        throw InputError(source + ": points[" + std::to_string(i) + "][" + std::to_string(k) +
                         "]: coordinate " + format_number(mesh_.points[i][k]) +
                         " beyond +-1e18, the largest coordinate taken (docs/meshes.md)");
  const std::size_t n = mesh_.tets.size();
  // Phase 1, adjacency (mesh/tet_adjacency.hpp): given by the caller (the mesh case reader
  // computes it for the overlap check) or computed here.
  if (neighbors.size() != n) neighbors = tet_neighbors(mesh_, source);
  // The boundary faces in the order of their sorted point triples (Embree's primitive order).
  // A face's plane (rule 1) is a function of its sorted point triple alone, so phase 2
  // recomputes it per cell, the same doubles.
  struct BoundaryRec {
    std::array<std::int32_t, 3> key;
    std::int32_t tet_k;
  };
  std::vector<BoundaryRec> brecs;
  for (std::size_t t = 0; t < n; ++t)
    for (std::size_t k = 0; k < 4; ++k)
      if (neighbors[t][k] < 0) brecs.push_back({face_key(mesh_, t, k), static_cast<std::int32_t>(4 * t + k)});
  std::sort(brecs.begin(), brecs.end(), [](const BoundaryRec& a, const BoundaryRec& b) { return a.key < b.key; });
  face_count_ = (4 * n + brecs.size()) / 2;
  boundary_.reserve(brecs.size());
  boundary_k_.reserve(brecs.size());
  for (const BoundaryRec& r : brecs) {
    Face f;
    f.points = r.key;
    f.normal = face_plane(mesh_, f.points);
    f.cells = {r.tet_k / 4, -1};
    boundary_.push_back(f);
    boundary_k_.push_back(static_cast<std::int8_t>(r.tet_k % 4));
  }
  std::vector<BoundaryRec>().swap(brecs);
  const auto plane = [&](const std::array<std::int32_t, 3>& key) { return face_plane(mesh_, key); };
  // +1 when the face's normal points out of cell t (away from its point k).
  const auto sign_of = [&](const std::array<std::int32_t, 3>& key, const Vec3& normal, std::size_t t, std::size_t k) {
    const Vec3& opposite = mesh_.points[static_cast<std::size_t>(mesh_.tets[t][k])];
    return normal.dot(opposite - mesh_.points[static_cast<std::size_t>(key[0])]) < 0.0 ? 1 : -1;
  };
  // Phase 2, the walk's per-cell records (see CellRecord): face k of cell t gets its face's normal
  // times the cell's sign (+1: the normal points out).
  // Each record formed whole and appended (a resize first zero-filled 128 B a tet, then
  // overwrote them: ~1% of the 105k load; issue 33).
  cells_.reserve(n);
  for (std::size_t t = 0; t < n; ++t) {
    CellRecord c;
    const auto& tet = mesh_.tets[t];
    const std::int32_t lowest = std::min({tet[0], tet[1], tet[2], tet[3]});
    c.first_point = lowest;
    c.second_point = lowest;
    c.k_second = -1;  // no face starts elsewhere (only with a repeated lowest index)
    c.anchor = tet[0];
    const std::array<std::array<std::int32_t, 3>, 4> keys = face_keys(mesh_, t);
    for (std::size_t k = 0; k < 4; ++k) {
      const std::array<std::int32_t, 3>& key = keys[k];
      const Vec3 normal = plane(key);
      const Vec3 outward = sign_of(key, normal, t, k) > 0 ? normal : Vec3(-normal);
      c.nx[k] = outward[0];
      c.ny[k] = outward[1];
      c.nz[k] = outward[2];
      c.next[k] = neighbors[t][k];
      if (key[0] != lowest) {
        c.k_second = static_cast<std::int32_t>(k);
        c.second_point = key[0];
      }
    }
    cells_.push_back(c);
  }
  TetNeighbors().swap(neighbors);
  // Eq. 9 per cell: the gradient (field() puts the anchor and its scalar back from the mesh).
  gradients_.resize(n);
  for (std::size_t t = 0; t < n; ++t) {
    std::array<Vec3, 4> x;
    std::array<double, 4> s{};
    for (std::size_t k = 0; k < 4; ++k) {
      x[k] = mesh_.points[mesh_.tets[t][k]];
      s[k] = mesh_.cell_scalars.empty() ? mesh_.scalars[mesh_.tets[t][k]] : mesh_.cell_scalars[t];
    }
    gradients_[t] = fit_linear_tet(x, s).gradient;
  }
  // Quadratic tets: their fields beside the walk's records (quadratic_tets.hpp).
  if (!mesh_.edge_nodes.empty() && mesh_.cell_scalars.empty()) {
    quadratic_.resize(n);
    for (std::size_t t = 0; t < n; ++t) quadratic_[t] = fit_quadratic_tet(mesh_, t);
  }
  const Bounds box = point_bounds(mesh_.points);
  box_min_ = box.lower;
  box_max_ = box.upper;
  diagonal_ = (box_max_ - box_min_).norm();
  std::vector<std::array<std::int32_t, 3>> tris;
  tris.reserve(boundary_.size());
  for (const Face& f : boundary_) {
    // Embree needs no particular winding (the filter decides entering vs leaving).
    tris.push_back(f.points);
  }
  first_hit_ = std::make_unique<BoundaryFirstHit>(mesh_.points, tris, box_min_, box_max_);
}

TetTraversal::~TetTraversal() = default;

LinearTetField TetTraversal::field(std::size_t cell) const {
  return cell_field(mesh_, gradients_[cell], cell, static_cast<std::size_t>(cells_[cell].anchor));
}

std::int32_t TetTraversal::neighbor(std::size_t cell, int k) const {
  return cells_[cell].next[static_cast<std::size_t>(k)];
}

struct TetTraversal::Walk {
  Vec3 o, d;
  double t_lo = 0.0;  // re-entry filter bound
  double tol = 0.0;   // how far before t_lo a non-strict re-entry may lie (rule 4)
  bool strict = false;
  const TetTraversal* self = nullptr;
};

// Rule 1: the crossing parameter of a face, the same double whichever cell asks (the sign of
// CellRecord::normal cancels exactly).
double TetTraversal::crossing(const Walk& w, std::size_t cell, int k) const {
  const CellRecord& r = cells_[cell];
  const Vec3 n = r.normal(k);
  return dot3(n, face_point(r, k) - w.o) / dot3(n, w.d);
}

struct FirstHitFilterAccess {
  // Rule 4: accept an entering boundary face at t_f >= t_lo - tol (or > t_lo when strict).
  static bool accept(const void* user, std::uint32_t prim) {
    const auto* w = static_cast<const TetTraversal::Walk*>(user);
    const TetTraversal& m = *w->self;
    const auto cell = static_cast<std::size_t>(m.boundary_[prim].cells[0]);
    const int k = m.boundary_k_[prim];
    const double dn = TetTraversal::dot3(m.cells_[cell].normal(k), w->d);  // sign * n.d
    if (!(dn < 0.0)) return false;  // leaving or parallel
    const double t = m.crossing(*w, cell, k);
    return w->strict ? t > w->t_lo : t >= w->t_lo - w->tol;
  }
};

// Rule 3: the cell around p = o + t d that the ray continues into.
bool TetTraversal::star_search(const Walk& w, std::int32_t from, double t, std::int32_t& cell,
                               double& t_out) const {
  const Vec3 p = w.o + t * w.d;
  const double tol = kStarTolerance * diagonal_;
  const double tol_t = kStarTolerance * (diagonal_ + std::fabs(t));
  // Per-thread scratch: a star search ends most rays (their exit through a boundary face), and
  // two fresh vectors per search were a malloc and a free each.
  thread_local std::vector<std::int32_t> queue, seen;
  queue.assign(1, from);
  seen.assign(1, from);
  constexpr std::size_t kMaxStar = 4096;
  bool found = false;
  double best = t;
  for (std::size_t q = 0; q < queue.size() && q < kMaxStar; ++q) {
    const auto c = static_cast<std::size_t>(queue[q]);
    const CellRecord& r = cells_[c];
    bool holds = true;
    // normal = sign * n exactly, so these are sign * n.(p - a) / |n| and sign * n.d. A neighbour
    // whose closure does not hold p is passed over at its first face that says so.
    std::array<double, 4> dist_from{};  // the first cell's four distances
    for (int k = 0; k < 4 && (holds || q == 0); ++k) {
      const Vec3 normal = r.normal(k);
      const double dist = normal.dot(p - face_point(r, k)) / normal.norm();
      dist_from[static_cast<std::size_t>(k)] = dist;
      if (dist > tol) holds = false;
    }
    if (!holds && q > 0) continue;
    double ta = -std::numeric_limits<double>::infinity(), tb = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 4; ++k) {
      const double dn = dot3(r.normal(k), w.d);
      if (dn > 0.0) tb = std::min(tb, crossing(w, c, k));
      else if (dn < 0.0) ta = std::max(ta, crossing(w, c, k));
    }
    if (ta <= t + tol_t && tb > best) {
      best = tb;
      cell = static_cast<std::int32_t>(c);
      found = true;
    }
    if (!holds) continue;
    for (int k = 0; k < 4; ++k) {
      const std::int32_t nb = neighbor(c, k);
      // The first cell's neighbour across face k has that face with the normal negated exactly and
      // the same point (rule 1), so its distance there is -dist_from[k], bit for bit: below -tol
      // it cannot hold p and would be passed over (issue 33, round 12: most star searches are a
      // ray's exit through the interior of a boundary face, where no neighbour holds p).
      if (q == 0 && dist_from[static_cast<std::size_t>(k)] < -tol) continue;
      if (nb >= 0 && std::find(seen.begin(), seen.end(), nb) == seen.end()) {
        seen.push_back(nb);
        queue.push_back(nb);
      }
    }
  }
  t_out = best;
  return found;
}

// One ray's walk between its boundary queries (trace_many keeps several in flight).
struct TetTraversal::WalkState {
  Walk w;
  RayTrace* out = nullptr;  // the crossings (trace, trace_many), or
  Ray* ray = nullptr;       // the segments' Ray (rays_many): walk_end copies them into it, far -> near
  // rays_many: the segments as the walk crosses the cells (near -> far), in a buffer of the
  // thread's kept from ray to ray, written by index (issue 33, round 21: emplace_back into the Ray
  // was a call per crossing, out of line with a vzeroupper, and the Ray was then reversed in place).
  std::vector<Segment>* buffer = nullptr;
  Segment* segments = nullptr;  // buffer->data()
  std::size_t segment_count = 0;
  double t_eye = 0.0;       // crossings are clipped here
  double t = 0.0;
  double t_end = 0.0;
  long steps = 0;
  long budget = 0;
  TraversalStats local;
  bool done = false;
};

void TetTraversal::trace(const ViewRay& ray, RayTrace& out, TraversalStats* stats) const {
  // Ray against the bounding box (slabs), to move the walk's origin just outside it.
  WalkState s;
  walk_begin(mesh_walk_start(ray, box_min_, box_max_, diagonal_), &out, nullptr, s);
  double t_near = 0.0;
  while (walk_query(s, t_near))
    walk_on(s, first_hit_->first(s.w.o, s.w.d, t_near, s.t_end, &FirstHitFilterAccess::accept, &s.w));
  walk_end(s, stats);
}

void TetTraversal::trace_many(const ViewRay* rays, std::size_t n, RayTrace* out, TraversalStats* stats) const {
  walk_many(rays, n, out, nullptr, stats);
}

void TetTraversal::rays_many(const ViewRay* rays, std::size_t n, const Rgb& background, Ray* out,
                             TraversalStats* stats) const {
  if (quadratic()) throw std::invalid_argument("rays_many: a mesh of quadratic tetrahedra has no linear segments");
  for (std::size_t i = 0; i < n; ++i) {
    out[i].background = background;
    out[i].quadratic.clear();
  }
  walk_many(rays, n, nullptr, out, stats);
}

void TetTraversal::walk_many(const ViewRay* rays, std::size_t n, RayTrace* out, Ray* ray_out,
                             TraversalStats* stats) const {
  constexpr int kPacket = BoundaryFirstHit::kPacket;
  thread_local std::array<std::vector<Segment>, kPacket> buffers;  // rays_many's, per lane
  for (std::size_t i0 = 0; i0 < n; i0 += kPacket) {
    const int m = static_cast<int>(std::min<std::size_t>(kPacket, n - i0));
    WalkState s[kPacket];
    Vec3 origin[kPacket], direction[kPacket];
    double t_near[kPacket], t_far[kPacket];
    bool active[kPacket];
    const void* users[kPacket];
    std::int64_t prim[kPacket];
    for (int i = 0; i < m; ++i) {
      const std::size_t r = i0 + static_cast<std::size_t>(i);
      walk_begin(mesh_walk_start(rays[r], box_min_, box_max_, diagonal_), out ? &out[r] : nullptr,
                 ray_out ? &ray_out[r] : nullptr, s[i]);
      s[i].buffer = &buffers[static_cast<std::size_t>(i)];
      s[i].segments = buffers[static_cast<std::size_t>(i)].data();
      users[i] = &s[i].w;
    }
    // Every ray that asks a boundary query (its first, or a re-entry after it left the mesh) in
    // one packet, then each walks on from its answer; the rays' own steps are trace()'s.
    for (;;) {
      bool any = false;
      for (int i = 0; i < m; ++i) {
        active[i] = walk_query(s[i], t_near[i]);
        any = any || active[i];
        origin[i] = s[i].w.o;
        direction[i] = s[i].w.d;
        t_far[i] = s[i].t_end;
      }
      if (!any) break;
      first_hit_->first_packet(origin, direction, t_near, t_far, active, m, &FirstHitFilterAccess::accept, users, prim);
      for (int i = 0; i < m; ++i)
        if (active[i]) walk_on(s[i], prim[i]);
    }
    for (int i = 0; i < m; ++i) walk_end(s[i], stats);
  }
}

void TetTraversal::walk_begin(const MeshWalkStart& start, RayTrace* out, Ray* ray, WalkState& s) const {
  s.out = out;
  s.ray = ray;
  s.segment_count = 0;
  if (out) {
    out->crossings.clear();
    out->direction = start.direction;
    out->origin = start.origin;
    out->t_eye = start.t_eye;
  }
  s.t_eye = start.t_eye;  // > 0 when the eye is inside the box: clip there
  s.local = TraversalStats{};
  s.local.rays = 1;
  s.done = start.empty;
  s.w.o = start.origin;
  s.w.d = start.direction;
  s.w.self = this;
  s.w.strict = false;
  s.t_end = start.t_end;
  s.budget = 8 * static_cast<long>(mesh_.tets.size()) + 1000;
  s.steps = 0;
  s.t = 0.0;
}

bool TetTraversal::walk_query(WalkState& s, double& t_near) const {
  if (s.done || s.steps >= s.budget) return false;
  // Outside the mesh: the next entering boundary face (rule 4).
  const double t = s.t;
  s.w.t_lo = t;
  s.w.tol = kStarTolerance * (diagonal_ + std::fabs(t));
  ++s.local.first_hit_queries;
  const double margin = 1e-5 * diagonal_ + 1e-6 * std::fabs(t);
  t_near = t - margin;
  return true;
}

void TetTraversal::walk_end(WalkState& s, TraversalStats* stats) const {
  if (s.ray)  // far -> near
    s.ray->segments.assign(std::make_reverse_iterator(s.segments + s.segment_count),
                           std::make_reverse_iterator(s.segments));
  if (s.steps >= s.budget) ++s.local.budget_exhausted;
  if (stats) stats->add(s.local);
}

// An AVX2 copy, picked at run time where the CPU has it, and the baseline one (issue 33, round 13:
// the four faces' crossing parameters in one AVX2 instruction each, two SSE2 ones otherwise).
// AVX2 only, not FMA: no multiply-add can be contracted (GCC 12 contracts in C++ even under
// -std=c++17 where the target has FMA: issue 33, round 20, src/CMakeLists.txt), so both copies
// compute the same IEEE operations in the same order, as the splitter's copies (model/pieces.cpp).
__attribute__((target_clones("avx2", "default"))) void TetTraversal::walk_on(WalkState& s, std::int64_t prim) const {
  if (prim < 0) {
    s.done = true;
    return;
  }
  const Walk& w = s.w;
  TraversalStats& local = s.local;
  long& steps = s.steps;
  const long budget = s.budget;
  double& t = s.t;
  const Vec3 d = w.d;
  const V4 dx = {d[0], d[0], d[0], d[0]}, dy = {d[1], d[1], d[1], d[1]}, dz = {d[2], d[2], d[2], d[2]};
  const V4 ox = {w.o[0], w.o[0], w.o[0], w.o[0]}, oy = {w.o[1], w.o[1], w.o[1], w.o[1]}, oz = {w.o[2], w.o[2], w.o[2], w.o[2]};
  // Inlined at both calls (GCC left the lambda out of line, a call and a vzeroupper per crossing).
  auto emit = [&](std::int32_t cell, double t_in, double t_out) __attribute__((always_inline)) {
    double a = std::max(t_in, s.t_eye);
    if (!(t_out > a)) return;
    ++local.crossings;
    const auto ci = static_cast<std::size_t>(cell);
    if (!quadratic_.empty()) {  // the hook for quadratic tets: s(t) of their quadratic field
      // Written in place: a CellCrossing built on the stack and copied stalled on store forwarding.
      CellCrossing& c = s.out->crossings.emplace_back();
      c.cell = cell;
      c.t_in = a;
      c.t_out = t_out;
      const std::array<double, 3> q = quadratic_tet_chord(quadratic_[ci], w.o + a * d, d);
      const double L = t_out - a;
      c.s_in = q[0];
      c.s_out = q[0] + L * (q[1] + L * q[2]);
      c.q = q[2];
      return;
    }
    // field(cell) and ray_parameters, inlined; the anchor's point index from the cell's record (in
    // the cache: the step just read it), not from mesh_.tets.
    const LinearTetField f = cell_field(mesh_, gradients_[ci], ci, static_cast<std::size_t>(cells_[ci].anchor));
    const Eq13 e = ray_parameters(f, w.o + a * d, d);
    const double length = t_out - a;
    if (s.ray) {  // rays_many: ray_from_trace's segment, the same doubles, written here
      if (s.segment_count == s.buffer->size()) {  // rare: the thread's buffer grows, once warm never
        s.buffer->resize(std::max<std::size_t>(256, 2 * s.buffer->size()));
        s.segments = s.buffer->data();
      }
      Segment& g = s.segments[s.segment_count++];
      g.length = length;
      g.scalar_far = e.v + e.w * length;
      g.scalar_exit = e.v;
    } else {
      CellCrossing& c = s.out->crossings.emplace_back();
      c.cell = cell;
      c.t_in = a;
      c.t_out = t_out;
      c.s_in = e.v;
      c.s_out = e.v + e.w * length;
    }
  };
  {
    std::int32_t cell = boundary_[static_cast<std::size_t>(prim)].cells[0];
    double t_in = std::max(t, crossing(w, static_cast<std::size_t>(cell), boundary_k_[static_cast<std::size_t>(prim)]));
    const double t_entered = t_in;
    int zero_steps = 0;
    bool progressed = false;
    while (++steps < budget) {
      // Leave the cell through the face with the smallest crossing parameter (rules 1, 2).
      const auto c = static_cast<std::size_t>(cell);
      const CellRecord& r = cells_[c];
      // Every face's t_f is computed, the four faces in the four lanes of the record's
      // components (one AVX2 instruction, or two SSE2 ones, per operation), and only those with
      // n.d > 0 are taken. The values, and so the
      // face chosen (the first of the smallest), are those of crossing() in a loop that skips the
      // others: the same IEEE operations in each lane. GCC compiles the scan below into branches;
      // the CPU then predicts the exit face and starts on the next cell before the division is
      // done, which measured faster than a branch-free choice (reports/scaling/NOTES.md, round 8:
      // 0.85 -> 1.07 s at 105k tets).
      // The cells behind every face are loaded first, before it is known which faces the ray
      // leaves through (the one it entered through is the cell just left, in the cache; round 8:
      // 1.06x at 1.05M tets against prefetching behind the leaving faces after the division).
      // Both cache lines of a record: the second holds nz, next and the points.
      for (std::size_t k = 0; k < 4; ++k) {
        const std::int32_t behind = r.next[k];
        const CellRecord* ahead = &cells_[behind >= 0 ? static_cast<std::size_t>(behind) : c];
        __builtin_prefetch(ahead);
        __builtin_prefetch(reinterpret_cast<const char*>(ahead) + 64);
      }
      const Vec3& p_first = mesh_.points[static_cast<std::size_t>(r.first_point)];
      const Vec3& p_second = mesh_.points[static_cast<std::size_t>(r.second_point)];
      alignas(16) double nd[4], tf[4];
      {
        const std::int64_t ks = r.k_second;
        const M4 second = {ks == 0 ? -1 : 0, ks == 1 ? -1 : 0, ks == 2 ? -1 : 0, ks == 3 ? -1 : 0};
        V4 nx, ny, nz;
        std::memcpy(&nx, r.nx.data(), sizeof nx);
        std::memcpy(&ny, r.ny.data(), sizeof ny);
        std::memcpy(&nz, r.nz.data(), sizeof nz);
        const V4 ndv = (nx * dx + ny * dy) + nz * dz;  // sign * n.d, exactly
        const V4 fx = {p_first[0], p_first[0], p_first[0], p_first[0]}, sx = {p_second[0], p_second[0], p_second[0], p_second[0]};
        const V4 fy = {p_first[1], p_first[1], p_first[1], p_first[1]}, sy = {p_second[1], p_second[1], p_second[1], p_second[1]};
        const V4 fz = {p_first[2], p_first[2], p_first[2], p_first[2]}, sz = {p_second[2], p_second[2], p_second[2], p_second[2]};
        const V4 ax = second ? sx : fx, ay = second ? sy : fy, az = second ? sz : fz;
        const V4 tfv = (nx * (ax - ox) + ny * (ay - oy)) + nz * (az - oz);
        std::memcpy(nd, &ndv, sizeof ndv);
        const V4 q = tfv / ndv;
        std::memcpy(tf, &q, sizeof q);
      }
      double t_min = std::numeric_limits<double>::infinity();
      int k_min = -1;
      for (int k = 0; k < 4; ++k) {
        const bool leaves = nd[k] > 0.0;
        const bool take = leaves & (tf[k] < t_min);
        t_min = take ? tf[k] : t_min;
        k_min = take ? k : k_min;
      }
      const double t_out = std::max(t_in, t_min);
      if (k_min < 0 || !std::isfinite(t_out)) break;  // cannot happen for a valid tet and d != 0
      if (t_out > t_in) {
        emit(cell, t_in, t_out);
        zero_steps = 0;
        progressed = true;
      } else {
        ++zero_steps;
        ++local.zero_length_steps;
      }
      t = t_out;
      std::int32_t next = r.next[static_cast<std::size_t>(k_min)];
      if (next < 0 || zero_steps > kZeroStepBudget) {  // rule 3
        ++local.star_searches;
        std::int32_t star_cell = -1;
        double star_out = t;
        if (star_search(w, cell, t, star_cell, star_out)) {
          emit(star_cell, t, star_out);
          progressed = true;
          zero_steps = 0;
          t = star_out;
          // Continue from star_cell's exit: find its exit face again from t.
          cell = star_cell;
          t_in = t;
          continue;
        }
        break;  // the ray leaves the mesh at t
      }
      ++local.face_steps;
      cell = next;
      t_in = t;
    }
    s.w.strict = !progressed;  // rule 4: an entry that made no progress must not be taken again
    if (!progressed) t = std::max(t, t_entered);
  }
}

Ray ray_from_trace(const RayTrace& trace, const Rgb& background) {
  Ray r;
  ray_from_trace(trace, background, r);
  return r;
}

void ray_from_trace(const RayTrace& trace, const Rgb& background, Ray& r) {
  r.background = background;
  const std::size_t n = trace.crossings.size();
  // Sized once and written field by field (a Segment pushed back went through the stack and
  // stalled on store forwarding: ~2.7% of a 105k-tet render; issue 33, round 12).
  r.segments.resize(n);
  bool quadratic = false;
  for (std::size_t i = 0; i < n; ++i) {
    const CellCrossing& c = trace.crossings[n - 1 - i];
    Segment& s = r.segments[i];
    s.length = c.t_out - c.t_in;
    s.scalar_far = c.s_out;
    s.scalar_exit = c.s_in;
    quadratic = quadratic || c.q != 0.0;
  }
  if (quadratic) {
    const auto it = std::find_if(trace.crossings.rbegin(), trace.crossings.rend(),  // the first in the Ray's order (far -> near)
                                 [](const CellCrossing& c) { return c.q != 0.0; });
    throw std::invalid_argument("ray_from_trace: a crossing of a quadratic tetrahedron (cell " +
                                std::to_string(it->cell) + ") is not a linear segment");
  }
}

Ray ray_with_quadratic_chords(const RayTrace& trace, const Rgb& background) {
  Ray r;
  r.background = background;
  r.segments.reserve(trace.crossings.size());
  bool quadratic = false;
  for (auto it = trace.crossings.rbegin(); it != trace.crossings.rend(); ++it) {
    r.segments.push_back(Segment{it->t_out - it->t_in, it->s_out, it->s_in});
    r.quadratic.push_back(it->q);
    quadratic = quadratic || it->q != 0.0;
  }
  if (!quadratic) r.quadratic.clear();
  return r;
}

Ray mesh_ray(const TetTraversal& mesh, const ViewRay& ray, const Rgb& background, TraversalStats* stats) {
  RayTrace trace;
  mesh.trace(ray, trace, stats);
  return ray_from_trace(trace, background);
}

}  // namespace rayint
