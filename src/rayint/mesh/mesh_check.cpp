// Orientation counts and the overlap check of a tetrahedral mesh (see mesh_check.hpp).
#include "rayint/mesh/mesh_check.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "rayint/core/error.hpp"

namespace rayint {
namespace {

struct Box {
  Vec3 lo, hi;
};

Box box_of_points(const std::array<Vec3, 4>& p) {
  Box b{p[0], p[0]};
  for (std::size_t k = 1; k < 4; ++k) {
    b.lo = b.lo.cwiseMin(p[k]);
    b.hi = b.hi.cwiseMax(p[k]);
  }
  return b;
}

std::array<Vec3, 4> tet_points(const TetMesh& m, std::size_t t) {
  std::array<Vec3, 4> p;
  for (std::size_t k = 0; k < 4; ++k) p[k] = m.points[static_cast<std::size_t>(m.tets[t][k])];
  return p;
}

Box box_of(const TetMesh& m, std::size_t t) { return box_of_points(tet_points(m, t)); }

// Projections of the 4 points on a unit axis: overlap of the two intervals (negative: a gap).
double overlap_on(const std::array<Vec3, 4>& a, const std::array<Vec3, 4>& b, const Vec3& axis) {
  double alo = a[0].dot(axis), ahi = alo, blo = b[0].dot(axis), bhi = blo;
  for (std::size_t k = 1; k < 4; ++k) {
    const double pa = a[k].dot(axis), pb = b[k].dot(axis);
    alo = std::min(alo, pa);
    ahi = std::max(ahi, pa);
    blo = std::min(blo, pb);
    bhi = std::max(bhi, pb);
  }
  return std::min(ahi, bhi) - std::max(alo, blo);
}

std::string cell_name(const TetMesh& m, std::size_t t) {
  if (m.info.cell_ids.size() == m.tets.size())
    return std::to_string(t) + " (cell " + std::to_string(m.info.cell_ids[t]) + " of the file)";
  return std::to_string(t);
}

}  // namespace

OrientationCounts orientation_counts(const TetMesh& mesh) {
  OrientationCounts c;
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) switch (classify_tet(mesh, t)) {
      case TetShape::Positive: ++c.positive; break;
      case TetShape::Inverted: ++c.inverted; break;
      case TetShape::ZeroVolume: ++c.zero_volume; break;
      case TetShape::Sliver: ++c.slivers; break;
    }
  return c;
}

namespace {

constexpr int kTetEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
constexpr int kTetFaces[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};

Vec3 face_normal(const std::array<Vec3, 4>& q, const int (&f)[3]) {
  const auto at = [&](int i) -> const Vec3& { return q[static_cast<std::size_t>(i)]; };
  return (at(f[1]) - at(f[0])).cross(at(f[2]) - at(f[0]));
}

// One tet's side of the separating-axis test, formed once and used against many others (the
// boundary check tests each tet against all the boundary tets near it): its points, the sum of
// its points, and per face the normal's length, the unit normal and the tet's own projection
// interval on it -- the same operations, in the same order, as forming them per pair. The face
// part is formed at the first pair the centroid axis does not settle (form_faces), so a tet
// tested once (the full check) costs what it did before.
struct TetAxes {
  std::array<Vec3, 4> p;
  Vec3 sum;
  bool faces = false;  // norm, unit, lo, hi formed
  std::array<double, 4> norm;
  std::array<Vec3, 4> unit;
  std::array<double, 4> lo, hi;
};

TetAxes tet_axes(const TetMesh& m, std::size_t t) {
  TetAxes A;
  A.p = tet_points(m, t);
  A.sum = A.p[0] + A.p[1] + A.p[2] + A.p[3];
  return A;
}

void form_faces(TetAxes& A) {
  if (A.faces) return;
  A.faces = true;
  for (std::size_t f = 0; f < 4; ++f) {
    const Vec3 axis = face_normal(A.p, kTetFaces[f]);
    A.norm[f] = axis.norm();
    A.unit[f] = A.norm[f] > 0 ? Vec3(axis / A.norm[f]) : Vec3::Zero();  // zero: never used (degenerate)
    A.lo[f] = A.hi[f] = A.p[0].dot(A.unit[f]);
    for (std::size_t k = 1; k < 4; ++k) {
      const double x = A.p[k].dot(A.unit[f]);
      A.lo[f] = std::min(A.lo[f], x);
      A.hi[f] = std::max(A.hi[f], x);
    }
  }
}

// tets_overlap with the pair's size (the larger box diagonal) given, tet a's axes and tet b's
// points. The answer is "no axis below separates", the same whatever the order the axes are tried
// in, and the same with a and b swapped (an edge axis only changes sign); the order only decides
// how soon a separated pair is settled. faces_first: a's face axes before the centroid axis, for
// a tet tested against many others (its faces formed once; on the 105k ball they settle 89.6k of
// the boundary check's 98.9k pairs, the centroid axis next 3.1k, issue 33).
bool overlap_exact(TetAxes& A, const std::array<Vec3, 4>& b, double size, bool faces_first) {
  const std::array<Vec3, 4>& a = A.p;
  const double tol = kOverlapTolerance * size;
  const double degenerate = 1e-12 * size * size;  // below: parallel edges, no axis
  const auto separates = [&](const Vec3& axis) {
    const double n = axis.norm();
    if (!(n > degenerate)) return false;
    return overlap_on(a, b, axis / n) <= tol;
  };
  // A cheap axis, the line through the two centroids: the projections being apart on any axis
  // proves the interiors disjoint, and it never changes the answer: the smallest overlap of two
  // convex polyhedra over all directions (their penetration depth) is attained on one of the 44
  // axes below, so an overlap <= tol here means one <= tol there too. On the generated balls it
  // settles most of the pairs that share no point (issue 33).
  const auto centroid_separates = [&] {
    const Vec3 axis = (b[0] + b[1] + b[2] + b[3]) - A.sum;
    const double len = axis.norm();
    return len > 1e-12 * size && overlap_on(a, b, axis / len) <= tol;
  };
  // a's faces: its own interval on each is formed once (most point-sharing pairs end here).
  // All four without a branch (whether one separates is the answer; which one is not needed).
  const auto a_face_separates = [&] {
    form_faces(A);
    bool any = false;
    for (std::size_t f = 0; f < 4; ++f) {
      double blo = b[0].dot(A.unit[f]), bhi = blo;
      for (std::size_t k = 1; k < 4; ++k) {
        const double x = b[k].dot(A.unit[f]);
        blo = std::min(blo, x);
        bhi = std::max(bhi, x);
      }
      any |= (A.norm[f] > degenerate) & (std::min(A.hi[f], bhi) - std::max(A.lo[f], blo) <= tol);
    }
    return any;
  };
  if (faces_first) {
    if (a_face_separates() || centroid_separates()) return false;
  } else if (centroid_separates() || a_face_separates()) {
    return false;
  }
  for (const auto& f : kTetFaces)
    if (separates(face_normal(b, f))) return false;
  for (const auto& ea : kTetEdges)
    for (const auto& eb : kTetEdges) {
      const Vec3 da = a[static_cast<std::size_t>(ea[1])] - a[static_cast<std::size_t>(ea[0])];
      const Vec3 db = b[static_cast<std::size_t>(eb[1])] - b[static_cast<std::size_t>(eb[0])];
      if (separates(da.cross(db))) return false;
    }
  return true;
}

}  // namespace

bool tets_overlap(const TetMesh& m, std::size_t ia, std::size_t ib) {
  const Box ba = box_of(m, ia), bb = box_of(m, ib);
  TetAxes A = tet_axes(m, ia);
  return overlap_exact(A, tet_points(m, ib), std::max((ba.hi - ba.lo).norm(), (bb.hi - bb.lo).norm()), false);
}

std::optional<std::pair<std::size_t, std::size_t>> find_overlapping_tets(const TetMesh& m, OverlapScope scope) {
  const std::size_t n = m.tets.size();
  if (n < 2) return std::nullopt;
  std::vector<Box> boxes(n);
  Box all{m.points[static_cast<std::size_t>(m.tets[0][0])], m.points[static_cast<std::size_t>(m.tets[0][0])]};
  Vec3 mean_extent = Vec3::Zero();
  for (std::size_t t = 0; t < n; ++t) {
    boxes[t] = box_of(m, t);
    all.lo = all.lo.cwiseMin(boxes[t].lo);
    all.hi = all.hi.cwiseMax(boxes[t].hi);
    mean_extent += boxes[t].hi - boxes[t].lo;
  }
  mean_extent /= static_cast<double>(n);
  // Grid cells of about the mean box extent, at most ~8 n of them. (For boxes of one size e,
  // the number of pairs met in the cells, ~ (h + e)^6 / h^3 for cells of size h, is smallest at
  // h = e.)
  std::array<long, 3> dims{};
  Vec3 cell;
  for (int k = 0; k < 3; ++k) {
    const double span = all.hi[k] - all.lo[k];
    const double want = std::max(mean_extent[k], span / std::cbrt(8.0 * static_cast<double>(n)));
    dims[static_cast<std::size_t>(k)] = span > 0 && want > 0 ? std::max(1L, std::min(1L << 20, static_cast<long>(span / want))) : 1;
    cell[k] = span > 0 ? span / static_cast<double>(dims[static_cast<std::size_t>(k)]) : 1.0;
  }
  const auto index = [&](const Vec3& p, int k) {
    const long i = static_cast<long>(std::floor((p[k] - all.lo[k]) / cell[k]));
    return static_cast<std::int32_t>(std::clamp(i, 0L, dims[static_cast<std::size_t>(k)] - 1));
  };
  // The grid cells a tet's box covers, lo[k]..hi[k] on axis k, and its tolerance (the box
  // diagonal; the pair's tolerance is kOverlapTolerance x the larger of the two).
  struct Span {
    std::array<std::int32_t, 3> lo, hi;
    double size;
  };
  std::vector<Span> spans(n);
  for (std::size_t t = 0; t < n; ++t) {
    Span& s = spans[t];
    for (int k = 0; k < 3; ++k) {
      s.lo[static_cast<std::size_t>(k)] = index(boxes[t].lo, k);
      s.hi[static_cast<std::size_t>(k)] = index(boxes[t].hi, k);
    }
    s.size = (boxes[t].hi - boxes[t].lo).norm();
  }
  // The members of every grid cell, in tet order: a counting sort by cell (linear in the number
  // of (cell, tet) records; issue 33). begin[c] .. begin[c + 1] indexes `members`.
  const auto n_cells = static_cast<std::size_t>(dims[0] * dims[1] * dims[2]);
  const auto key = [&](long i, long j, long k) { return static_cast<std::size_t>(i + dims[0] * (j + dims[1] * k)); };
  const auto for_cells = [&](const Span& sp, auto&& f) {
    for (long k = sp.lo[2]; k <= sp.hi[2]; ++k)
      for (long j = sp.lo[1]; j <= sp.hi[1]; ++j)
        for (long i = sp.lo[0]; i <= sp.hi[0]; ++i) f(key(i, j, k));
  };
  std::vector<std::size_t> begin(n_cells + 1, 0);
  for (std::size_t t = 0; t < n; ++t) for_cells(spans[t], [&](std::size_t c) { ++begin[c + 1]; });
  for (std::size_t c = 0; c < n_cells; ++c) begin[c + 1] += begin[c];
  std::vector<std::uint32_t> members(begin[n_cells]);
  for (std::size_t t = n; t-- > 0;)  // backwards, each cell filled from its end: tet order
    for_cells(spans[t], [&](std::size_t c) { members[--begin[c + 1]] = static_cast<std::uint32_t>(t); });
  // Now begin[c + 1] is where cell c starts.
  begin.erase(begin.begin());
  begin.push_back(members.size());
  std::optional<std::pair<std::size_t, std::size_t>> first;
  const auto test = [&](std::size_t a, std::size_t b) {
    if (a > b) std::swap(a, b);
    if (first && std::make_pair(a, b) >= *first) return;
    const Box& A = boxes[a];
    const Box& B = boxes[b];
    const double tol = kOverlapTolerance * std::max(spans[a].size, spans[b].size);
    for (int k = 0; k < 3; ++k)
      if (std::min(A.hi[k], B.hi[k]) - std::max(A.lo[k], B.lo[k]) <= tol) return;
    if (scope == OverlapScope::disjoint_pairs) {
      for (const std::int32_t pa : m.tets[a])
        for (const std::int32_t pb : m.tets[b])
          if (pa == pb) return;
    }
    TetAxes axes_a = tet_axes(m, a);
    if (overlap_exact(axes_a, tet_points(m, b), std::max(spans[a].size, spans[b].size), false)) first = std::make_pair(a, b);
  };
  // A pair is tested once: in the grid cell of the lower corner of the boxes' intersection,
  // max(A.lo, B.lo), whose cell is the larger of the two lower cells on each axis (the cell index
  // is monotone in the coordinate). Both boxes cover the cell c of the run, so their lower cells
  // are at most c: the corner is in c iff on every axis one of the two starts in c. The members
  // are sorted into 8 lists by the axes on which they start in c (a bit each); only lists whose
  // bits cover all three axes are paired, so the pairs tested elsewhere are never visited.
  std::array<std::vector<std::uint32_t>, 8> by_start;
  for (std::size_t cell_key = 0; cell_key < n_cells; ++cell_key) {
    const std::size_t r0 = begin[cell_key], r1 = begin[cell_key + 1];
    if (r1 - r0 < 2) continue;
    const auto d0 = static_cast<std::size_t>(dims[0]), d1 = static_cast<std::size_t>(dims[1]);
    const std::array<std::int32_t, 3> c{static_cast<std::int32_t>(cell_key % d0),
                                        static_cast<std::int32_t>((cell_key / d0) % d1),
                                        static_cast<std::int32_t>(cell_key / (d0 * d1))};
    for (auto& l : by_start) l.clear();
    for (std::size_t x = r0; x < r1; ++x) {
      const Span& sp = spans[members[x]];
      const unsigned bits = (sp.lo[0] == c[0] ? 1U : 0U) | (sp.lo[1] == c[1] ? 2U : 0U) | (sp.lo[2] == c[2] ? 4U : 0U);
      by_start[bits].push_back(members[x]);
    }
    const auto& all_axes = by_start[7];
    for (std::size_t x = 0; x < all_axes.size(); ++x)
      for (std::size_t y = x + 1; y < all_axes.size(); ++y) test(all_axes[x], all_axes[y]);
    for (unsigned ma = 0; ma < 7; ++ma)
      for (unsigned mb = ma + 1; mb < 8; ++mb)
        if ((ma | mb) == 7)
          for (const std::uint32_t a : by_start[ma])
            for (const std::uint32_t b : by_start[mb]) test(a, b);
  }
  return first;
}

namespace {

// The sweep direction of the lemma (mesh_check.hpp): any fixed direction; this one is parallel to
// no face of a box or Kuhn mesh.
const Vec3 kSweep(0.8, 0.45, 0.2);

// The boundary faces of tet t (next[t][k] < 0) whose outward normal n may have n . kSweep > 0, as
// a mask (bit k: the face opposite point k). A face is left out only when n . kSweep <= 0 is
// certain: the face normal N = (b - a) x (c - a), its sign against the opposite point, and
// N . kSweep are formed in doubles; each component is a difference of two products l - r, whose
// rounding error (differences, products, the difference and the sum: < 10 eps (|l| + |r|) per
// component x |kSweep_i|) is below the bounds used, 1e-14 x sum_i |kSweep_i| (|l_i| + |r_i|) and
// 1e-14 x sum_i |d_i| (|l_i| + |r_i|) (d: opposite point - a). Within them the face is kept.
unsigned facing_faces(const TetMesh& m, std::size_t t, const std::array<std::int32_t, 4>& nt) {
  const std::array<Vec3, 4> p = tet_points(m, t);
  unsigned mask = 0;
  for (std::size_t k = 0; k < 4; ++k) {
    if (nt[k] >= 0) continue;
    const Vec3& a = p[static_cast<std::size_t>(kTetFaces[k][0])];
    const Vec3 u = p[static_cast<std::size_t>(kTetFaces[k][1])] - a, v = p[static_cast<std::size_t>(kTetFaces[k][2])] - a;
    const Vec3 l(u[1] * v[2], u[2] * v[0], u[0] * v[1]), r(u[2] * v[1], u[0] * v[2], u[1] * v[0]);
    const Vec3 N = l - r, mag = l.cwiseAbs() + r.cwiseAbs();
    const Vec3 d = p[k] - a;
    const double side = N.dot(d), side_err = 1e-14 * mag.dot(d.cwiseAbs());
    const double s = N.dot(kSweep), s_err = 1e-14 * mag.dot(kSweep.cwiseAbs());
    // Outward normal: -N when the opposite point is on N's side. Left out when certainly
    // n . kSweep <= 0, i.e. the tet certainly on N's side and N . kSweep >= its error, or
    // certainly on the other side and N . kSweep <= -its error.
    // Only where the bounds hold: products far from underflow (an absolute error of ~1e-322 each)
    // and from overflow; otherwise (and for NaN) the face is kept.
    const bool in_range = side_err > 1e-280 && side_err < 1e280 && s_err > 1e-280 && s_err < 1e280;
    const bool out = in_range && ((side > side_err && s >= s_err) || (side < -side_err && s <= -s_err));
    if (!out) mask |= 1U << k;
  }
  return mask;
}

// The box of the points of tet t on the faces in mask (bit k: the face opposite point k).
Box faces_box(const TetMesh& m, std::size_t t, unsigned mask) {
  Box b{};
  bool first = true;
  for (std::size_t j = 0; j < 4; ++j) {
    if ((mask & ~(1U << j)) == 0) continue;  // point j is on none of them (the only one is opposite it)
    const Vec3& q = m.points[static_cast<std::size_t>(m.tets[t][j])];
    if (first) {
      b.lo = b.hi = q;
      first = false;
    } else {
      b.lo = b.lo.cwiseMin(q);
      b.hi = b.hi.cwiseMax(q);
    }
  }
  return b;
}

}  // namespace

bool boundary_tets_overlap_free(const TetMesh& m, const TetNeighbors& next) {
  const std::size_t n = m.tets.size();
  if (next.size() != n) return false;
  if (n < 2) return true;
  // The members: the tets with a boundary face that may face kSweep, in tet order. One 64-byte
  // record each with all a candidate pair reads of it (the box of the points of those faces, the
  // tet's box diagonal: the pair tolerance's scale, the tet).
  struct alignas(64) Member {
    Box faces;
    double size;
    std::uint32_t tet;
  };
  const auto open = [&next](std::size_t t) {
    const std::array<std::int32_t, 4>& nt = next[t];
    return nt[0] < 0 || nt[1] < 0 || nt[2] < 0 || nt[3] < 0;
  };
  std::size_t n_open = 0;
  for (std::size_t t = 0; t < n; ++t) n_open += open(t) ? 1 : 0;
  std::vector<Member> bm;
  bm.reserve(n_open);  // about half of it used: the pages are touched only as members are written
  for (std::size_t t = 0; t < n; ++t) {
    if (!open(t)) continue;
    const std::array<std::int32_t, 4>& nt = next[t];
    const unsigned facing = facing_faces(m, t, nt);
    if (facing == 0) continue;
    Member M{};
    const Box tb = box_of(m, t);
    M.size = (tb.hi - tb.lo).norm();
    M.tet = static_cast<std::uint32_t>(t);
    M.faces = faces_box(m, t, facing);
    bm.push_back(M);
  }
  if (bm.empty()) return false;  // a finite mesh has a boundary facing every way: let the full check decide
  if (bm.size() >= (std::size_t{1} << 29)) return false;  // let the full check decide
  // A grid of the members' face boxes: cells of their mean extent, at most ~|bm| of them (on the
  // 105k ball 8 |bm| cost more in fresh pages than they saved), filled by a counting sort as in
  // find_overlapping_tets.
  Box all = bm[0].faces;
  Vec3 mean_extent = Vec3::Zero();
  for (const Member& M : bm) {
    all.lo = all.lo.cwiseMin(M.faces.lo);
    all.hi = all.hi.cwiseMax(M.faces.hi);
    mean_extent += M.faces.hi - M.faces.lo;
  }
  mean_extent /= static_cast<double>(bm.size());
  std::array<long, 3> dims{};
  Vec3 inv_cell;
  for (int k = 0; k < 3; ++k) {
    const double span = all.hi[k] - all.lo[k];
    const double want = std::max(mean_extent[k], span / std::cbrt(static_cast<double>(bm.size())));
    dims[static_cast<std::size_t>(k)] = span > 0 && want > 0 ? std::max(1L, std::min(1L << 20, static_cast<long>(span / want))) : 1;
    inv_cell[k] = span > 0 ? static_cast<double>(dims[static_cast<std::size_t>(k)]) / span : 1.0;
  }
  // The cell of coordinate x on axis k: (x - lo) x (cells / span), clamped to the grid in double
  // (where truncation is the floor and the cast cannot overflow). Monotone in x, which is all the
  // pair bookkeeping below needs.
  const auto index = [&](double x, int k) {
    const double top = static_cast<double>(dims[static_cast<std::size_t>(k)] - 1);
    return static_cast<long>(std::clamp((x - all.lo[k]) * inv_cell[k], 0.0, top));
  };
  const auto key = [&](long i, long j, long k) { return static_cast<std::size_t>(i + dims[0] * (j + dims[1] * k)); };
  const auto n_cells = static_cast<std::size_t>(dims[0] * dims[1] * dims[2]);
  const auto cells_of = [&](const Box& b) {
    std::array<long, 6> sp{};  // lo i, j, k, hi i, j, k
    for (int k = 0; k < 3; ++k) {
      sp[static_cast<std::size_t>(k)] = index(b.lo[k], k);
      sp[static_cast<std::size_t>(k + 3)] = index(b.hi[k], k);
    }
    return sp;
  };
  // The grid's arrays in 32-bit words (fresh pages cost ~10 us each on the VM of issue 33): the
  // (cell, member) records' offsets, fewer than 2^32 (checked), and per record the member (an
  // index into bm, below 2^29: checked) with, in the top 3 bits, the axes on which that box
  // starts in the grid cell (bit k: its lower cell index on axis k is the cell's). A member's
  // cells are formed again in each pass instead of kept.
  std::vector<std::uint32_t> begin(n_cells + 1, 0);
  std::size_t records = 0;
  for (const Member& M : bm) {
    const auto sp = cells_of(M.faces);
    records += static_cast<std::size_t>((sp[3] - sp[0] + 1) * (sp[4] - sp[1] + 1) * (sp[5] - sp[2] + 1));
    if (records >= (std::size_t{1} << 32)) return false;  // let the full check decide
    for (long k = sp[2]; k <= sp[5]; ++k)
      for (long j = sp[1]; j <= sp[4]; ++j)
        for (long i = sp[0]; i <= sp[3]; ++i) ++begin[key(i, j, k) + 1];
  }
  for (std::size_t c = 0; c < n_cells; ++c) begin[c + 1] += begin[c];
  // Each cell is filled from its end (begin[c + 1] counts down to cell c's start), members
  // backwards: in member order within a cell.
  std::vector<std::uint32_t> members(records);
  for (std::size_t x = bm.size(); x-- > 0;) {
    const auto sp = cells_of(bm[x].faces);
    for (long k = sp[2]; k <= sp[5]; ++k)
      for (long j = sp[1]; j <= sp[4]; ++j)
        for (long i = sp[0]; i <= sp[3]; ++i) {
          const std::uint32_t bits = (i == sp[0] ? 1U : 0U) | (j == sp[1] ? 2U : 0U) | (k == sp[2] ? 4U : 0U);
          members[--begin[key(i, j, k) + 1]] = static_cast<std::uint32_t>(x) | (bits << 29);
        }
  }
  // Now begin[c + 1] is where cell c starts: cell c is begin[c + 1] .. begin[c + 2].
  begin.erase(begin.begin());
  begin.push_back(static_cast<std::uint32_t>(records));
  // Summed counts: sat at (i, j, k) = the records in the cells below (i, j, k) on all three axes,
  // so whether a block of cells holds any is 8 lookups, whatever its size (sums modulo 2^32:
  // exact, fewer than 2^32 records). Most tets of a mesh meet no member's cell.
  const auto sx = static_cast<std::size_t>(dims[0]) + 1, sy = static_cast<std::size_t>(dims[1]) + 1;
  std::vector<std::uint32_t> sat(sx * sy * (static_cast<std::size_t>(dims[2]) + 1), 0);
  const auto at = [&](long i, long j, long k) {
    return static_cast<std::size_t>(i) + sx * (static_cast<std::size_t>(j) + sy * static_cast<std::size_t>(k));
  };
  for (long k = 0; k < dims[2]; ++k)
    for (long j = 0; j < dims[1]; ++j)
      for (long i = 0; i < dims[0]; ++i) {
        const std::size_t c = key(i, j, k);
        sat[at(i + 1, j + 1, k + 1)] = (begin[c + 1] - begin[c]) + sat[at(i, j + 1, k + 1)] + sat[at(i + 1, j, k + 1)] +
                                       sat[at(i + 1, j + 1, k)] - sat[at(i, j, k + 1)] - sat[at(i, j + 1, k)] -
                                       sat[at(i + 1, j, k)] + sat[at(i, j, k)];
      }
  const auto records_in = [&](const std::array<long, 6>& sp) {
    const long i0 = sp[0], j0 = sp[1], k0 = sp[2], i1 = sp[3] + 1, j1 = sp[4] + 1, k1 = sp[5] + 1;
    return sat[at(i1, j1, k1)] - sat[at(i0, j1, k1)] - sat[at(i1, j0, k1)] - sat[at(i1, j1, k0)] + sat[at(i0, j0, k1)] +
           sat[at(i0, j1, k0)] + sat[at(i1, j0, k0)] - sat[at(i0, j0, k0)];
  };
  const auto apart = [](const Box& a, const Box& b) {  // closed boxes without a common point
    return (a.hi[0] < b.lo[0]) | (a.lo[0] > b.hi[0]) | (a.hi[1] < b.lo[1]) | (a.lo[1] > b.hi[1]) | (a.hi[2] < b.lo[2]) |
           (a.lo[2] > b.hi[2]);
  };
  // Every tet t against the members whose face boxes meet its box.
  constexpr std::size_t kChunk = 256;
  std::array<std::uint32_t, kChunk> pass;
  std::size_t own = 0;  // the first member whose tet is >= t (members are in tet order)
  for (std::size_t t = 0; t < n; ++t) {
    TetAxes axes = tet_axes(m, t);
    const Box b = box_of_points(axes.p);
    if (apart(b, all)) continue;
    const auto sp = cells_of(b);
    if (records_in(sp) == 0) continue;
    const double size_t_ = (b.hi - b.lo).norm();
    const std::array<std::int32_t, 4> nt = next[t];
    while (own < bm.size() && bm[own].tet < t) ++own;
    // t a member too: a pair of members (t, u) is met from both sides when each one's face box
    // meets the other's box; then it is tested from the lower tet only.
    const Box* t_faces = own < bm.size() && bm[own].tet == t ? &bm[own].faces : nullptr;
    for (long ck = sp[2]; ck <= sp[5]; ++ck)
      for (long cj = sp[1]; cj <= sp[4]; ++cj)
        for (long ci = sp[0]; ci <= sp[3]; ++ci) {
          const std::size_t c = key(ci, cj, ck);
          // Each pair once: in the grid cell of the lower corner of the two boxes (the cell index
          // is monotone in the coordinate), max(lo_t, lo_u) on each axis. Where t starts before
          // this cell on an axis, u must start in it there: those axes are `need`.
          const std::uint32_t need = ((ci > sp[0] ? 1U : 0U) | (cj > sp[1] ? 2U : 0U) | (ck > sp[2] ? 4U : 0U)) << 29;
          // In chunks, without branches on the two filters that reject most: the members passing
          // each are packed into a buffer, in order, and only those go on.
          for (std::size_t r0 = begin[c]; r0 < begin[c + 1]; r0 += kChunk) {
            const std::size_t r1 = std::min<std::size_t>(begin[c + 1], r0 + kChunk);
            std::size_t n_start = 0;
            for (std::size_t r = r0; r < r1; ++r) {
              pass[n_start] = members[r] & ((1U << 29) - 1);
              n_start += (members[r] & need) == need ? 1 : 0;
            }
            std::size_t n_box = 0;
            for (std::size_t q = 0; q < n_start; ++q) {
              pass[n_box] = pass[q];
              n_box += apart(b, bm[pass[q]].faces) ? 0 : 1;
            }
            for (std::size_t q = 0; q < n_box; ++q) {
              const Member& M = bm[pass[q]];
              const std::size_t u = M.tet;
              if (u == t) continue;
              const auto ui = static_cast<std::int32_t>(u);
              // Face neighbours lie on opposite sides of their face (tet_neighbors checked it).
              if (nt[0] == ui || nt[1] == ui || nt[2] == ui || nt[3] == ui) continue;
              const std::array<Vec3, 4> up = tet_points(m, u);
              if (t_faces && u < t && !apart(box_of_points(up), *t_faces)) continue;
              if (overlap_exact(axes, up, std::max(size_t_, M.size), true)) return false;
            }
          }
        }
  }
  return true;
}

std::optional<std::pair<std::size_t, std::size_t>> find_overlapping_tets(const TetMesh& mesh, const TetNeighbors& next,
                                                                          OverlapScope scope) {
  if (boundary_tets_overlap_free(mesh, next)) return std::nullopt;
  return find_overlapping_tets(mesh, scope);
}

void refuse_overlapping_tets(const TetMesh& mesh, const TetNeighbors& next, const std::string& source,
                             const std::string& tets_field) {
  if (boundary_tets_overlap_free(mesh, next)) return;
  refuse_overlapping_tets(mesh, source, tets_field);
}

void refuse_overlapping_tets(const TetMesh& mesh, const std::string& source, const std::string& tets_field) {
  const auto pair = find_overlapping_tets(mesh, OverlapScope::disjoint_pairs);
  if (!pair) return;
  field::fail(source, tets_field,
              "tetrahedra " + cell_name(mesh, pair->first) + " and " + cell_name(mesh, pair->second) +
                  " overlap (their interiors intersect: two meshes appended without shared points?); "
                  "a ray would integrate that volume twice");
}

}  // namespace rayint
