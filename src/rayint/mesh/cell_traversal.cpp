// Own-interpolation traversal of a mesh of linear cells (see cell_traversal.hpp; rules 1-4 there).
#include "rayint/mesh/cell_traversal.hpp"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "rayint/core/error.hpp"
#include "rayint/geometry/bounds.hpp"
#include "rayint/mesh/embree_ray.hpp"
#include "rayint/core/format.hpp"

namespace rayint {

void CellTraversalStats::add(const CellTraversalStats& o) {
  add_counters(*this, o, kCellTraversalCounters);
}

LinearCellType linear_type_of(MeshCellType type) {
  QuadraticCellType q;
  if (quadratic_cell_type_from_vtk(static_cast<int>(type), q)) return quadratic_corner_type(q);
  return static_cast<LinearCellType>(static_cast<int>(type));
}

namespace {
// The largest point coordinate taken: as tet_traversal.cpp's (a tested, conservative bound).
constexpr double kMaxCoordinate = 1e18;
}  // namespace

// ---- The walk's state ------------------------------------------------------------------------

struct CellTraversal::Walk {
  Vec3 o, d;
  double t_lo = 0.0;   // re-entry: hits at or beyond t_lo - tol
  double tol = 0.0;
  const CellTraversal* self = nullptr;
  // Best accepted boundary hit so far (first-hit query).
  double best_t = std::numeric_limits<double>::infinity();
  double best_far = 0.0;
  Vec3 best_p = Vec3::Zero();  // the chord's p_hint
  std::int64_t best_face = -1;
  std::vector<int> best_exit;
  long failed = 0;
  // next_cell's scratch, reused from step to step of the ray (no allocation per step).
  mutable std::vector<int> candidate_faces;
  mutable std::vector<std::int32_t> tried, points;
  std::optional<RayFrame> frame;  // the ray's frame for the bilinear faces (set with o, d)
  ViewRay ray() const { return ViewRay{o, d}; }
  double slack(double t) const { return kCellEntrySlack * (self->diagonal_ + std::fabs(t)); }
};

// ---- Boundary first hit: Embree user geometry, every decision in double ----------------------

struct CellFirstHitAccess {
  static void intersect_face(const CellTraversal::Walk& w, std::uint32_t prim, RTCRayHit& rh,
                             unsigned geom_id);
};

class CellBoundaryFirstHit {
 public:
  explicit CellBoundaryFirstHit(const CellTraversal& mesh);
  ~CellBoundaryFirstHit() {
    if (scene_) rtcReleaseScene(scene_);
    if (device_) rtcReleaseDevice(device_);
  }
  CellBoundaryFirstHit(const CellBoundaryFirstHit&) = delete;
  CellBoundaryFirstHit& operator=(const CellBoundaryFirstHit&) = delete;
  // Fills w.best_*: the nearest boundary face hit at t >= w.t_lo - w.tol whose cell holds the ray
  // beyond max(hit, t_lo).
  void first(CellTraversal::Walk& w, double t_near, double t_far) const;
  const LocalFrame& frame() const { return frame_; }

 private:
  RTCDevice device_ = nullptr;
  LocalFrame frame_;  // Embree's geometry and rays (mesh/embree_ray.hpp)
  RTCScene scene_ = nullptr;
  std::vector<std::array<float, 6>> bounds_;
  friend void cell_face_bounds(const RTCBoundsFunctionArguments* args);
};

namespace {

struct QueryContext {
  RTCIntersectContext base;  // first member: Embree passes a pointer to it
  CellTraversal::Walk* walk;
};

}  // namespace

void cell_face_bounds(const RTCBoundsFunctionArguments* args) {
  const auto* self = static_cast<const CellBoundaryFirstHit*>(args->geometryUserPtr);
  const std::array<float, 6>& b = self->bounds_[args->primID];
  RTCBounds* o = args->bounds_o;
  o->lower_x = b[0], o->lower_y = b[1], o->lower_z = b[2];
  o->upper_x = b[3], o->upper_y = b[4], o->upper_z = b[5];
}

namespace {

// A quadratic boundary face's patch nodes (corners, mid-edge nodes, centre) from the mesh's points.
PatchNodes patch_nodes(const CellMesh& mesh, const CellTraversal::BoundaryFace& f) {
  PatchNodes nodes{};
  for (int k = 0; k < f.count; ++k) {
    nodes[static_cast<std::size_t>(k)] = mesh.points[static_cast<std::size_t>(f.points[static_cast<std::size_t>(k)])];
    nodes[static_cast<std::size_t>(f.count + k)] = mesh.points[static_cast<std::size_t>(f.mids[static_cast<std::size_t>(k)])];
  }
  if (f.centre >= 0) nodes[static_cast<std::size_t>(2 * f.count)] = mesh.points[static_cast<std::size_t>(f.centre)];
  return nodes;
}

void cell_face_intersect(const RTCIntersectFunctionNArguments* args) {
  if (args->valid[0] == 0) return;
  const auto* ctx = reinterpret_cast<const QueryContext*>(args->context);
  auto* rh = reinterpret_cast<RTCRayHit*>(args->rayhit);  // N == 1 (rtcIntersect1)
  CellFirstHitAccess::intersect_face(*ctx->walk, args->primID, *rh, args->geomID);
}

void cell_face_occluded(const RTCOccludedFunctionNArguments*) {}  // never queried

}  // namespace

CellBoundaryFirstHit::CellBoundaryFirstHit(const CellTraversal& mesh) {
  device_ = rtcNewDevice("threads=1");
  if (!device_) throw std::runtime_error("Embree: rtcNewDevice failed");
  scene_ = rtcNewScene(device_);
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  const std::size_t n = mesh.boundary_face_count();
  // The pad covers 1e-7 of the diagonal and the rounding of moving a bound into the frame (half
  // an ulp of the largest coordinate, or of the centre, each; the scaling is exact).
  const Vec3 box_lo = mesh.box_min(), box_hi = mesh.box_max();
  frame_ = LocalFrame::of(box_lo, box_hi);
  const double largest = std::max(box_lo.cwiseAbs().maxCoeff(), box_hi.cwiseAbs().maxCoeff());
  const double pad = frame_.length(1e-7 * (box_hi - box_lo).norm() + 8.0 * std::numeric_limits<double>::epsilon() * largest);
  bounds_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& f = mesh.boundary_face(i);
    Vec3 lo = mesh.mesh().points[static_cast<std::size_t>(f.points[0])], hi = lo;
    for (int k = 1; k < f.count; ++k) {
      const Vec3& p = mesh.mesh().points[static_cast<std::size_t>(f.points[static_cast<std::size_t>(k)])];
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    if (f.mids[0] >= 0)  // a quadratic patch: the box of its Bernstein control points
      patch_control_box(patch_nodes(mesh.mesh(), f), f.count, f.centre >= 0, lo, hi);
    const Vec3 flo = frame_.point(lo), fhi = frame_.point(hi);
    for (int k = 0; k < 3; ++k) {
      // Padded, then rounded outward to float.
      bounds_[i][static_cast<std::size_t>(k)] = std::nextafter(static_cast<float>(flo[k] - pad), -HUGE_VALF);
      bounds_[i][static_cast<std::size_t>(k + 3)] = std::nextafter(static_cast<float>(fhi[k] + pad), HUGE_VALF);
    }
  }
  if (n > 0) {
    RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(geom, static_cast<unsigned>(n));
    rtcSetGeometryUserData(geom, this);
    rtcSetGeometryBoundsFunction(geom, cell_face_bounds, nullptr);
    rtcSetGeometryIntersectFunction(geom, cell_face_intersect);
    rtcSetGeometryOccludedFunction(geom, cell_face_occluded);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene_, geom);
    rtcReleaseGeometry(geom);
  }
  rtcCommitScene(scene_);
  if (rtcGetDeviceError(device_) != RTC_ERROR_NONE)
    throw std::runtime_error("Embree: scene build failed (error " +
                             std::to_string(static_cast<int>(rtcGetDeviceError(device_))) + ")");
}

void CellBoundaryFirstHit::first(CellTraversal::Walk& w, double t_near, double t_far) const {
  QueryContext ctx;
  rtcInitIntersectContext(&ctx.base);
  ctx.walk = &w;
  w.best_t = std::numeric_limits<double>::infinity();
  w.best_face = -1;
  RTCRayHit rh;
  const double frame_far = frame_.length(t_far);
  init_ray_hit(rh, frame_, w.o, w.d, t_near,
               std::isfinite(frame_far) && frame_far < 3e38 ? std::nextafter(static_cast<float>(frame_far), HUGE_VALF)
                                                            : std::numeric_limits<float>::infinity());
  rtcIntersect1(scene_, &ctx.base, &rh);
}

void CellFirstHitAccess::intersect_face(const CellTraversal::Walk& cw, std::uint32_t prim, RTCRayHit& rh,
                                        unsigned geom_id) {
  auto& w = const_cast<CellTraversal::Walk&>(cw);
  const CellTraversal& m = *w.self;
  const CellTraversal::BoundaryFace& f = m.boundary_[prim];
  std::vector<double> hit_t;
  if (f.mids[0] >= 0) {  // a quadratic patch, nodes in canonical order
    for (const PatchHit& h : intersect_quadratic_face(patch_nodes(m.mesh_, f), f.count, f.centre >= 0, w.ray()))
      hit_t.push_back(h.t);
  } else {
    double ts[2];
    const int n = m.face_hits(static_cast<std::size_t>(f.face), w, ts);
    hit_t.assign(ts, ts + n);
  }
  for (const double t_hit : hit_t) {
    if (!(t_hit >= w.t_lo - w.tol) || !(t_hit < w.best_t)) continue;
    const double t_start = std::max(t_hit, w.t_lo);
    double t_far = 0.0;
    std::vector<int> exit_faces;
    bool failed = false;
    Vec3 p_hint;
    const bool holds = m.continue_in(static_cast<std::size_t>(f.cell), w, t_start, t_far, &exit_faces, &failed, &p_hint);
    if (failed) ++w.failed;
    if (!holds) continue;
    w.best_t = t_hit;
    w.best_far = t_far;
    w.best_p = p_hint;
    w.best_face = prim;
    w.best_exit = std::move(exit_faces);
    // Let Embree cull boxes beyond this hit (rounded up: a nearer hit is never culled).
    rh.ray.tfar = std::nextafter(static_cast<float>(m.first_hit_->frame().length(t_hit)), HUGE_VALF);
    rh.hit.geomID = geom_id;
    rh.hit.primID = prim;
    rh.hit.u = rh.hit.v = 0.0f;
    rh.hit.Ng_x = rh.hit.Ng_y = 0.0f;
    rh.hit.Ng_z = 1.0f;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    break;  // hits are sorted by t: the first accepted is this face's nearest
  }
}

// ---- Planar faces ----------------------------------------------------------------------------
//
// A quadrilateral A B C D (canonical order) is planar when its bilinear patch's twist term
// A - B + C - D has no component along the normal n = (C - A) x (D - B) beyond rounding:
// |n^ . (A - B + C - D)| <= kAffineTolerance x (largest |coordinate| of its nodes). The corners
// then lie within 1/4 of that (16 eps x magnitude) of the plane through their mean, and the patch
// within 3/4 of it: the plane is the patch to the rounding of the node coordinates themselves
// (the same threshold, and origin, as make_linear_cell's affine test). It must also be strictly
// convex (every corner turns the same way about n), so that its inside is the four edge tests
// below. A triangle is always planar (n = (B - A) x (C - A)). Every other face stays a bilinear
// patch (intersect_face).
//
// A planar face's hit: t = (offset - n . o) / (n . d), inside when the hit point is on the inner
// side of every edge k, (e_k x (P - V_k)) . n >= -edge_slack_k with edge_slack_k = kFaceSlack x
// L x |n| x |e_k| (L the face's longest diagonal or edge): a distance of kFaceSlack x L beyond
// the edge, what intersect_face's parametric slack kFaceSlack allows. One routine (plane_hit) for
// both paths below, so a face's t has the same bits in both of its cells.

CellTraversal::FaceGeometry CellTraversal::planar_face_geometry(const std::array<Vec3, 4>& nodes, int count) {
  FaceGeometry g;
  g.nodes = nodes;
  g.count = count;
  const Vec3 &A = nodes[0], &B = nodes[1], &C = nodes[2], &D = nodes[3];
  double magnitude = 0.0, diameter = 0.0;
  for (int k = 0; k < count; ++k) {
    magnitude = std::max(magnitude, nodes[static_cast<std::size_t>(k)].cwiseAbs().maxCoeff());
    diameter = std::max(diameter, (nodes[static_cast<std::size_t>((k + 1) % count)] - nodes[static_cast<std::size_t>(k)]).norm());
  }
  if (count == 3) {
    g.normal = (B - A).cross(C - A);
    g.offset = g.normal.dot(A + B + C) / 3.0;
  } else {
    g.normal = (C - A).cross(D - B);
    const double nn = g.normal.norm();
    if (!(nn > 0.0) || !(std::abs(g.normal.dot((A - B) + (C - D))) <= kAffineTolerance * magnitude * nn)) return g;
    for (int k = 0; k < 4; ++k) {  // strictly convex
      const Vec3& p = nodes[static_cast<std::size_t>((k + 3) % 4)];
      const Vec3& v = nodes[static_cast<std::size_t>(k)];
      const Vec3& q = nodes[static_cast<std::size_t>((k + 1) % 4)];
      if (!((v - p).cross(q - v).dot(g.normal) > 0.0)) return g;
    }
    diameter = std::max((C - A).norm(), (D - B).norm());
    g.offset = g.normal.dot((A + B) + (C + D)) / 4.0;
  }
  const double nn = g.normal.norm();
  if (!(nn > 0.0)) return g;
  for (int k = 0; k < count; ++k)
    g.edge_slack[static_cast<std::size_t>(k)] =
        kFaceSlack * diameter * nn * (nodes[static_cast<std::size_t>((k + 1) % count)] - nodes[static_cast<std::size_t>(k)]).norm();
  g.planar = true;
  return g;
}

std::size_t CellTraversal::planar_face_count() const {
  return static_cast<std::size_t>(std::count_if(faces_.begin(), faces_.end(), [](const FaceGeometry& g) { return g.planar; }));
}

namespace {
// The parameter where the line o + t d meets the plane n . x = offset (inf or NaN when parallel).
double plane_hit(const Vec3& normal, double offset, const Vec3& o, const Vec3& d, double& den) {
  den = normal.dot(d);
  return (offset - normal.dot(o)) / den;
}
}  // namespace

int CellTraversal::face_hits(std::size_t i, const Walk& w, double* t) const {
  const FaceGeometry& g = faces_[i];
  if (!g.planar) {
    const FaceHits h = intersect_face(g.nodes, g.count, w.ray(), *w.frame);
    for (int k = 0; k < h.count; ++k) t[k] = h.hit[static_cast<std::size_t>(k)].t;
    return h.count;
  }
  double den;
  const double th = plane_hit(g.normal, g.offset, w.o, w.d, den);
  if (!std::isfinite(th)) return 0;
  const Vec3 P = w.o + th * w.d;
  for (int k = 0; k < g.count; ++k) {
    const Vec3& a = g.nodes[static_cast<std::size_t>(k)];
    const Vec3& b = g.nodes[static_cast<std::size_t>((k + 1) % g.count)];
    if (!((b - a).cross(P - a).dot(g.normal) >= -g.edge_slack[static_cast<std::size_t>(k)])) return 0;
  }
  t[0] = th;
  return 1;
}

bool CellTraversal::continue_in_linear(std::size_t c, const Walk& w, double t, double& t_far,
                                       std::vector<int>* exit_faces, bool* failed, Vec3* p_hint) const {
  const auto base = static_cast<std::size_t>(neighbor_offsets_[c]);
  const int n_faces = linear_face_count(cells_[c].type);
  const double slack = w.slack(t);
  if (clip_[c]) {
    // An affine cell is the convex polyhedron of its face planes: the chord is [last entry, first
    // exit] over the planes (no inverse map; the integral needs no Newton start).
    double t_near = -std::numeric_limits<double>::infinity(), t_exit = std::numeric_limits<double>::infinity();
    std::array<double, 6> exit_t{};
    exit_t.fill(std::numeric_limits<double>::quiet_NaN());
    for (int f = 0; f < n_faces; ++f) {
      const FaceGeometry& g = faces_[static_cast<std::size_t>(cell_faces_[base + static_cast<std::size_t>(f)])];
      const double out = face_out_[base + static_cast<std::size_t>(f)];
      double den;
      const double th = plane_hit(g.normal, g.offset, w.o, w.d, den);
      if (den == 0.0) {  // parallel: the whole line is outside this plane, or inside
        if (out * (g.offset - g.normal.dot(w.o)) < 0.0) return false;
        continue;
      }
      if (out * den > 0.0) {
        exit_t[static_cast<std::size_t>(f)] = th;
        t_exit = std::min(t_exit, th);
      } else {
        t_near = std::max(t_near, th);
      }
    }
    if (!(t_near < t_exit) || !(t_near <= t + slack) || !(t_exit > t)) return false;
    t_far = t_exit;
    if (p_hint) *p_hint = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
    if (exit_faces) {
      exit_faces->clear();
      const double s = w.slack(t_far);
      for (int f = 0; f < n_faces; ++f)
        if (std::fabs(exit_t[static_cast<std::size_t>(f)] - t_far) <= s) exit_faces->push_back(f);
    }
    return true;
  }
  // Every face's hits, then chord()'s classification of the intervals between them.
  std::array<ChordFaceHit, 2 * 6> hits{};
  int n_hits = 0;
  for (int f = 0; f < n_faces; ++f) {
    double th[2];
    const int k = face_hits(static_cast<std::size_t>(cell_faces_[base + static_cast<std::size_t>(f)]), w, th);
    for (int h = 0; h < k; ++h) hits[static_cast<std::size_t>(n_hits++)] = {th[h], f};
  }
  std::sort(hits.begin(), hits.begin() + n_hits, [](const ChordFaceHit& a, const ChordFaceHit& b) {
    return a.t < b.t || (a.t == b.t && a.face < b.face);
  });
  std::array<double, 2 * 6> ts{};
  int n_ts = 0;
  for (int h = 0; h < n_hits; ++h)
    if (n_ts == 0 || ts[static_cast<std::size_t>(n_ts - 1)] != hits[static_cast<std::size_t>(h)].t)
      ts[static_cast<std::size_t>(n_ts++)] = hits[static_cast<std::size_t>(h)].t;
  std::array<ChordInterval, 2 * 6> intervals{};
  bool chord_failed = false;
  const int n_iv = classify_chord_intervals(cells_[c], w.ray(), ts.data(), n_ts, intervals.data(), chord_failed);
  if (chord_failed && failed) *failed = true;
  return hold_interval(intervals.data(), n_iv, hits.data(), n_hits, w, t, t_far, exit_faces, p_hint);
}

bool CellTraversal::hold_interval(const ChordInterval* intervals, std::size_t n_intervals, const ChordFaceHit* hits,
                                  std::size_t n_hits, const Walk& w, double t, double& t_far,
                                  std::vector<int>* exit_faces, Vec3* p_hint) {
  const double slack = w.slack(t);
  for (std::size_t i = 0; i < n_intervals; ++i) {
    const ChordInterval& iv = intervals[i];
    if (!(iv.t_near <= t + slack) || !(iv.t_far > t)) continue;
    t_far = iv.t_far;
    if (p_hint) *p_hint = iv.p_mid;
    if (exit_faces) {
      exit_faces->clear();
      const double s = w.slack(t_far);
      for (std::size_t h = 0; h < n_hits; ++h)
        if (std::fabs(hits[h].t - t_far) <= s && std::find(exit_faces->begin(), exit_faces->end(), hits[h].face) == exit_faces->end())
          exit_faces->push_back(hits[h].face);
    }
    return true;
  }
  return false;
}

// ---- Building ----------------------------------------------------------------------------------

CellTraversal::CellTraversal(CellMesh mesh, const std::string& source) : mesh_(std::move(mesh)) {
  for (std::size_t i = 0; i < mesh_.points.size(); ++i)
    for (int k = 0; k < 3; ++k)
      if (!(std::fabs(mesh_.points[i][k]) <= kMaxCoordinate))
        throw InputError(source + ": points[" + std::to_string(i) + "][" + std::to_string(k) + "]: coordinate " +
                         format_number(mesh_.points[i][k]) +
                         " beyond +-1e18, the largest coordinate taken (docs/meshes.md)");
  const std::size_t n = mesh_.cell_count();
  if (n == 0) throw InputError(source + ": cells: no volume cells");
  if (n > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max() / 8))
    throw InputError(source + ": cells: " + std::to_string(n) + " cells; at most 2^28 - 1 are supported");
  // Cells in their own interpolation.
  cells_.reserve(n);
  std::vector<Vec3> x;
  std::vector<double> v;
  for (std::size_t c = 0; c < n; ++c) {
    const std::int32_t* ids = mesh_.cell(c);
    x.clear();
    v.clear();
    for (std::size_t k = 0; k < mesh_.nodes_of(c); ++k) {
      const auto p = static_cast<std::size_t>(ids[k]);
      x.push_back(mesh_.points[p]);
      v.push_back(mesh_.cell_scalars.empty() ? mesh_.scalars[p] : mesh_.cell_scalars[c]);
    }
    try {
      QuadraticCellType q;
      if (quadratic_cell_type_from_vtk(static_cast<int>(mesh_.types[c]), q)) {
        if (quadratic_index_.empty()) quadratic_index_.assign(n, -1);
        quadratic_index_[c] = static_cast<std::int32_t>(quadratic_.size());
        quadratic_.push_back(make_quadratic_cell(q, x, v));
        // The corners' linear cell: its faces' corners key the adjacency below.
        const auto corners = static_cast<std::ptrdiff_t>(linear_node_count(quadratic_corner_type(q)));
        cells_.push_back(make_linear_cell(quadratic_corner_type(q), std::vector<Vec3>(x.begin(), x.begin() + corners),
                                          std::vector<double>(v.begin(), v.begin() + corners)));
      } else {
        cells_.push_back(make_linear_cell(linear_type_of(mesh_.types[c]), x, v));
      }
    } catch (const std::invalid_argument& e) {
      const long long id = c < mesh_.info.cell_ids.size() ? mesh_.info.cell_ids[c] : static_cast<long long>(c);
      throw InputError(source + ": cells[" + std::to_string(id) + "]: " + e.what());
    }
  }
  // Faces keyed by sorted point ids (triangles padded with -1 in front).
  struct Rec {
    std::array<std::int32_t, 4> key;
    std::int32_t cell;
    std::int32_t local;
  };
  std::vector<Rec> recs;
  neighbor_offsets_.assign(n + 1, 0);
  for (std::size_t c = 0; c < n; ++c) {
    const LinearCellType type = cells_[c].type;
    const int faces = linear_face_count(type);
    neighbor_offsets_[c + 1] = neighbor_offsets_[c] + faces;
    for (int f = 0; f < faces; ++f) {
      const FaceNodes fn = linear_face(type, f);
      Rec r{{-1, -1, -1, -1}, static_cast<std::int32_t>(c), f};
      for (int k = 0; k < fn.count; ++k)
        r.key[static_cast<std::size_t>(k)] = mesh_.cell(c)[fn.node[static_cast<std::size_t>(k)]];
      std::sort(r.key.begin(), r.key.end());
      recs.push_back(r);
    }
  }
  std::sort(recs.begin(), recs.end(), [](const Rec& a, const Rec& b) {
    return a.key != b.key ? a.key < b.key : (a.cell != b.cell ? a.cell < b.cell : a.local < b.local);
  });
  neighbors_.assign(static_cast<std::size_t>(neighbor_offsets_[n]), -1);
  cell_faces_.assign(static_cast<std::size_t>(neighbor_offsets_[n]), -1);
  faces_.reserve(recs.size() / 2 + 1);
  // A face's nodes in canonical order (of their global ids, as chord() puts them) and its plane.
  const auto face_geometry = [&](std::int32_t cell, std::int32_t local) {
    const auto c = static_cast<std::size_t>(cell);
    const FaceNodes fn = linear_face(cells_[c].type, local);
    std::array<std::int64_t, 4> ids{};
    for (int k = 0; k < fn.count; ++k) ids[static_cast<std::size_t>(k)] = mesh_.cell(c)[fn.node[static_cast<std::size_t>(k)]];
    const std::array<int, 4> perm = canonical_face_order(ids, fn.count);
    std::array<Vec3, 4> nodes{};
    for (int k = 0; k < fn.count; ++k)
      nodes[static_cast<std::size_t>(k)] = mesh_.points[static_cast<std::size_t>(ids[static_cast<std::size_t>(perm[static_cast<std::size_t>(k)])])];
    return planar_face_geometry(nodes, fn.count);
  };
  const auto slot = [&](const Rec& r) {
    return static_cast<std::size_t>(neighbor_offsets_[static_cast<std::size_t>(r.cell)] + r.local);
  };
  for (std::size_t i = 0; i < recs.size();) {
    std::size_t j = i + 1;
    while (j < recs.size() && recs[j].key == recs[i].key) ++j;
    if (j - i > 2)
      throw InputError(source + ": cells[" + std::to_string(recs[i + 2].cell) + "]: a face is shared by more than two cells (also cells[" +
                       std::to_string(recs[i].cell) + "] and cells[" + std::to_string(recs[i + 1].cell) + "])");
    const auto face_index = static_cast<std::int32_t>(face_count_);
    for (std::size_t k = i; k < j; ++k) cell_faces_[slot(recs[k])] = face_index;
    faces_.push_back(face_geometry(recs[i].cell, recs[i].local));
    if (j - i == 2) {
      neighbors_[slot(recs[i])] = recs[i + 1].cell;
      neighbors_[slot(recs[i + 1])] = recs[i].cell;
    } else {
      const Rec& r = recs[i];
      const auto c = static_cast<std::size_t>(r.cell);
      const FaceNodes fn = linear_face(cells_[c].type, r.local);
      std::array<std::int64_t, 4> ids{};
      for (int k = 0; k < fn.count; ++k) ids[static_cast<std::size_t>(k)] = mesh_.cell(c)[fn.node[static_cast<std::size_t>(k)]];
      const std::array<int, 4> perm = canonical_face_order(ids, fn.count);
      BoundaryFace b;
      b.count = fn.count;
      b.cell = r.cell;
      b.local = r.local;
      b.face = face_index;
      for (int k = 0; k < fn.count; ++k)
        b.points[static_cast<std::size_t>(k)] = static_cast<std::int32_t>(ids[static_cast<std::size_t>(perm[static_cast<std::size_t>(k)])]);
      if (const QuadraticCell* q = quadratic_cell(c)) {  // the patch's nodes in the same canonical order
        std::array<std::int64_t, kMaxQuadraticNodes> all{};
        for (std::size_t k = 0; k < mesh_.nodes_of(c); ++k) all[k] = mesh_.cell(c)[k];
        const QuadraticFacePatch patch = canonical_quadratic_face(*q, r.local, all.data());
        for (int k = 0; k < fn.count; ++k) {
          b.points[static_cast<std::size_t>(k)] = mesh_.cell(c)[patch.local[static_cast<std::size_t>(k)]];
          b.mids[static_cast<std::size_t>(k)] = mesh_.cell(c)[patch.local[static_cast<std::size_t>(fn.count + k)]];
        }
        if (patch.centre) b.centre = mesh_.cell(c)[patch.local[static_cast<std::size_t>(2 * fn.count)]];
      }
      boundary_.push_back(b);
    }
    ++face_count_;
    i = j;
  }
  std::vector<Rec>().swap(recs);
  // Which way each planar face's normal points from each of its cells, and the cells whose chord
  // is the clip of their face planes: affine (the map is linear: the cell is exactly the convex
  // polyhedron its planar faces bound) and every face planar by the test above.
  face_out_.assign(cell_faces_.size(), 1);
  clip_.assign(n, 0);
  for (std::size_t c = 0; c < n; ++c) {
    if (quadratic_cell(c) != nullptr) continue;
    const LinearCell& cell = cells_[c];
    const int nodes = linear_node_count(cell.type);
    Vec3 centre = Vec3::Zero();
    for (int k = 0; k < nodes; ++k) centre += cell.x[static_cast<std::size_t>(k)];
    centre /= nodes;
    bool all_planar = true;
    for (int f = 0; f < linear_face_count(cell.type); ++f) {
      const auto slot_cf = static_cast<std::size_t>(neighbor_offsets_[c] + f);
      const FaceGeometry& g = faces_[static_cast<std::size_t>(cell_faces_[slot_cf])];
      all_planar = all_planar && g.planar;
      face_out_[slot_cf] = g.normal.dot(centre) < g.offset ? 1 : -1;
    }
    clip_[c] = cell.affine && all_planar;
  }
  // Cells around each point (for exits through edges and vertices).
  point_cells_offsets_.assign(mesh_.points.size() + 1, 0);
  for (std::int32_t p : mesh_.connectivity) ++point_cells_offsets_[static_cast<std::size_t>(p) + 1];
  for (std::size_t p = 0; p < mesh_.points.size(); ++p) point_cells_offsets_[p + 1] += point_cells_offsets_[p];
  point_cells_.assign(mesh_.connectivity.size(), -1);
  {
    std::vector<std::int32_t> fill(point_cells_offsets_.begin(), point_cells_offsets_.end() - 1);
    for (std::size_t c = 0; c < n; ++c)
      for (std::size_t k = 0; k < mesh_.nodes_of(c); ++k)
        point_cells_[static_cast<std::size_t>(fill[static_cast<std::size_t>(mesh_.cell(c)[k])]++)] = static_cast<std::int32_t>(c);
  }
  const Bounds box = point_bounds(mesh_.points);
  box_min_ = box.lower;
  box_max_ = box.upper;
  diagonal_ = (box_max_ - box_min_).norm();
  // Each linear cell's corner box (next_cell's star filter), padded by 1e-7 of the diagonal plus
  // the largest |coordinate|: >= 1e5 x the face hits' reach beyond their face (kFaceSlack 1e-12 of
  // the face's edges) and >= 1e8 ulps of the coordinates (the rounding of x(t) and of the hits,
  // also for a mesh far from the origin). A quadratic cell's curved edges leave its corners' box:
  // its box is unbounded (never skipped).
  cell_box_pad_ = 1e-7 * (diagonal_ + std::max(box_min_.cwiseAbs().maxCoeff(), box_max_.cwiseAbs().maxCoeff()));
  cell_box_.resize(n);
  constexpr double kInf = std::numeric_limits<double>::infinity();
  for (std::size_t c = 0; c < n; ++c) {
    if (quadratic_cell(c) != nullptr) {
      cell_box_[c] = {-kInf, -kInf, -kInf, kInf, kInf, kInf};
      continue;
    }
    const LinearCell& cell = cells_[c];
    Vec3 lo = cell.x[0], hi = cell.x[0];
    for (int k = 1; k < linear_node_count(cell.type); ++k) {
      lo = lo.cwiseMin(cell.x[static_cast<std::size_t>(k)]);
      hi = hi.cwiseMax(cell.x[static_cast<std::size_t>(k)]);
    }
    cell_box_[c] = {lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]};
  }
  first_hit_ = std::make_unique<CellBoundaryFirstHit>(*this);
}

CellTraversal::~CellTraversal() = default;

std::array<std::int64_t, kMaxLinearNodes> CellTraversal::global_ids(std::size_t c) const {
  std::array<std::int64_t, kMaxLinearNodes> ids{};
  // A quadratic cell's corners come first: the linear cell's ids.
  for (std::size_t k = 0; k < std::min<std::size_t>(mesh_.nodes_of(c), kMaxLinearNodes); ++k) ids[k] = mesh_.cell(c)[k];
  return ids;
}

// ---- Walking -----------------------------------------------------------------------------------

Chord CellTraversal::cell_chord(std::size_t c, const ViewRay& ray) const {
  if (const QuadraticCell* q = quadratic_cell(c)) {
    std::array<std::int64_t, kMaxQuadraticNodes> ids{};
    for (std::size_t k = 0; k < mesh_.nodes_of(c); ++k) ids[k] = mesh_.cell(c)[k];
    return quadratic_chord(*q, ray, ids.data());
  }
  const auto ids = global_ids(c);
  return chord(cells_[c], ray, ids.data());
}

bool CellTraversal::continue_in(std::size_t c, const Walk& w, double t, double& t_far,
                                std::vector<int>* exit_faces, bool* failed, Vec3* p_hint) const {
  if (quadratic_cell(c) == nullptr) return continue_in_linear(c, w, t, t_far, exit_faces, failed, p_hint);
  const Chord ch = cell_chord(c, w.ray());
  if (ch.failed && failed) *failed = true;
  return hold_interval(ch.intervals.data(), ch.intervals.size(), ch.hits.data(), ch.hits.size(), w, t, t_far, exit_faces,
                       p_hint);
}

// Rule 2: the cell that continues the ray at t after `from` (left through `exit_faces`).
bool CellTraversal::next_cell(const Walk& w, std::size_t from, const std::vector<int>& exit_faces, double t,
                              std::int32_t& cell, double& t_far, std::vector<int>& faces,
                              CellTraversalStats& stats, bool& failed, Vec3& p_hint) const {
  double best = t;
  bool found = false;
  std::vector<int>& cand_faces = w.candidate_faces;
  const auto consider = [&](std::int32_t c) {
    double far = 0.0;
    Vec3 p;
    if (continue_in(static_cast<std::size_t>(c), w, t, far, &cand_faces, &failed, &p) && far > best) {
      best = far;
      p_hint = p;
      cell = c;
      faces = cand_faces;
      found = true;
    }
  };
  std::vector<std::int32_t>& tried = w.tried;  // each candidate cell is considered once
  tried.clear();
  const auto consider_once = [&](std::int32_t c) {
    if (std::find(tried.begin(), tried.end(), c) != tried.end()) return;
    tried.push_back(c);
    consider(c);
  };
  for (int f : exit_faces) {
    const std::int32_t nb = neighbors_[static_cast<std::size_t>(neighbor_offsets_[from] + f)];
    if (nb >= 0) consider_once(nb);
  }
  if (found) {
    ++stats.face_steps;
    t_far = best;
    return true;
  }
  // An edge or vertex exit: every cell sharing a point with the exit faces (or with the cell).
  std::vector<std::int32_t>& points = w.points;
  points.clear();
  const LinearCellType type = cells_[from].type;
  if (exit_faces.empty()) {
    for (std::size_t k = 0; k < mesh_.nodes_of(from); ++k) points.push_back(mesh_.cell(from)[k]);
  } else {
    for (int f : exit_faces) {
      const FaceNodes fn = linear_face(type, f);
      for (int k = 0; k < fn.count; ++k) points.push_back(mesh_.cell(from)[fn.node[static_cast<std::size_t>(k)]]);
    }
  }
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  tried.push_back(static_cast<std::int32_t>(from));
  // A linear cell that holds t has a point of its chord within slack(t) of x(t) (rule 2), and its
  // chord lies in its corners' convex hull up to the face hits' slack (kFaceSlack of the face) and
  // rounding, far inside cell_box_pad_: a candidate whose padded corner box misses x(t) by more
  // than slack(t) cannot hold t and is not solved (on a mesh's boundary exit every cell around the
  // exit face's corners was solved before; `rayint bench` twisted12: ~6 per exit). Quadratic
  // cells' boxes are unbounded.
  const Vec3 x = w.o + t * w.d;
  const double reach = cell_box_pad_ + w.slack(t);
  const auto may_hold = [&](std::int32_t c) {
    const std::array<double, 6>& b = cell_box_[static_cast<std::size_t>(c)];
    for (int k = 0; k < 3; ++k)
      if (!(x[k] >= b[static_cast<std::size_t>(k)] - reach && x[k] <= b[static_cast<std::size_t>(k + 3)] + reach)) return false;
    return true;
  };
  for (std::int32_t p : points)
    for (std::int32_t i = point_cells_offsets_[static_cast<std::size_t>(p)]; i < point_cells_offsets_[static_cast<std::size_t>(p) + 1]; ++i) {
      const std::int32_t c = point_cells_[static_cast<std::size_t>(i)];
      if (may_hold(c)) consider_once(c);
    }
  if (found) {
    ++stats.star_steps;
    t_far = best;
  }
  return found;
}

void CellTraversal::trace(const ViewRay& ray, CellTrace& out, CellTraversalStats* stats) const {
  out.chords.clear();
  out.failed_chords = 0;
  CellTraversalStats local;
  local.rays = 1;
  const MeshWalkStart start = mesh_walk_start(ray, box_min_, box_max_, diagonal_);
  out.direction = start.direction;
  out.origin = start.origin;
  out.t_eye = start.t_eye;
  if (start.empty) {
    if (stats) stats->add(local);
    return;
  }
  Walk w;
  w.o = out.origin;
  w.d = start.direction;
  w.frame.emplace(w.ray());
  w.self = this;
  const double t_end = start.t_end;
  const long budget = 8 * static_cast<long>(cells_.size()) + 1000;
  long steps = 0;
  double t = 0.0;
  bool failed = false;
  std::vector<int> exit_faces, next_faces;
  const auto emit = [&](std::int32_t c, double a, double b, const Vec3& p) {
    ++local.chords;
    out.chords.push_back({c, a, b, p});
  };
  while (steps < budget) {
    // Rule 3: outside the mesh, the next entry beyond t.
    w.t_lo = t;
    w.tol = w.slack(t);
    ++local.first_hit_queries;
    const double margin = 1e-5 * diagonal_ + 1e-6 * std::fabs(t);
    first_hit_->first(w, t - margin, t_end);
    if (w.best_face < 0) break;
    std::int32_t cell = boundary_[static_cast<std::size_t>(w.best_face)].cell;
    double t_in = std::max(t, w.best_t);
    double t_out = w.best_far;
    Vec3 p_hint = w.best_p;
    exit_faces = w.best_exit;
    while (++steps < budget) {
      emit(cell, t_in, t_out, p_hint);  // t_out > t_in (continue_in)
      t = t_out;
      std::int32_t next = -1;
      double next_far = 0.0;
      if (!next_cell(w, static_cast<std::size_t>(cell), exit_faces, t, next, next_far, next_faces, local, failed, p_hint))
        break;  // left the mesh at t
      cell = next;
      t_in = t;
      t_out = next_far;
      std::swap(exit_faces, next_faces);
    }
  }
  if (steps >= budget) ++local.budget_exhausted;
  // Chords that failed to classify (Newton) anywhere on this ray's candidates.
  if (failed || w.failed > 0) {
    out.failed_chords = 1 + w.failed;
    local.failed_chords += out.failed_chords;
  }
  if (stats) stats->add(local);
}

CellRayResult CellTraversal::integrate(const CellTrace& trace, const LinearCellIntegrator& integrator,
                                       const Rgb& background) const {
  CellRayResult r;
  const ViewRay ray{trace.origin, trace.direction};
  CellPieceIntegral acc;
  acc.converged = true;
  bool any = false;
  if (trace.failed_chords > 0) {
    r.failed_chords += trace.failed_chords;
    r.converged = false;
    r.failure = "a cell's chord could not be located (inverse map did not converge)";
  }
  for (const CellChordOnRay& c : trace.chords) {
    const double a = std::max(c.t_in, trace.t_eye);
    if (!(c.t_out > a)) continue;
    const QuadraticCell* q = quadratic_cell(static_cast<std::size_t>(c.cell));
    const CellPieceIntegral p = q != nullptr ? integrator.integrate(*q, ray, a, c.t_out)
                                             : integrator.integrate(cells_[static_cast<std::size_t>(c.cell)], ray, a, c.t_out, &c.p_hint);
    ++r.chords;
    if (!p.converged) {
      ++r.failed_chords;
      if (r.converged) r.failure = std::string("cell ") + std::to_string(c.cell) + ": " + p.failure;
      r.converged = false;
    }
    acc = any ? composite(acc, p) : p;
    any = true;
  }
  if (any) {
    r.emission = acc.emission;
    r.optical_depth = acc.optical_depth;
    r.error_estimate = acc.error_estimate;
  }
  for (std::size_t ch = 0; ch < kChannels; ++ch)
    r.intensity[ch] = r.emission[ch] + std::exp(-r.optical_depth[ch]) * background[ch];
  return r;
}

}  // namespace rayint
