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

Box box_of(const TetMesh& m, std::size_t t) {
  Box b{m.points[static_cast<std::size_t>(m.tets[t][0])], m.points[static_cast<std::size_t>(m.tets[t][0])]};
  for (std::size_t k = 1; k < 4; ++k) {
    b.lo = b.lo.cwiseMin(m.points[static_cast<std::size_t>(m.tets[t][k])]);
    b.hi = b.hi.cwiseMax(m.points[static_cast<std::size_t>(m.tets[t][k])]);
  }
  return b;
}

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

bool tets_overlap(const TetMesh& m, std::size_t ia, std::size_t ib) {
  std::array<Vec3, 4> a, b;
  for (std::size_t k = 0; k < 4; ++k) {
    a[k] = m.points[static_cast<std::size_t>(m.tets[ia][k])];
    b[k] = m.points[static_cast<std::size_t>(m.tets[ib][k])];
  }
  const Box ba = box_of(m, ia), bb = box_of(m, ib);
  const double size = std::max((ba.hi - ba.lo).norm(), (bb.hi - bb.lo).norm());
  const double tol = kOverlapTolerance * size;
  static constexpr int kEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  static constexpr int kFaces[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  const auto separates = [&](const Vec3& axis) {
    const double n = axis.norm();
    if (!(n > 1e-12 * size * size)) return false;  // parallel edges: no axis
    return overlap_on(a, b, axis / n) <= tol;
  };
  for (const auto* p : {&a, &b})
    for (const auto& f : kFaces) {
      const auto& q = *p;
      if (separates((q[static_cast<std::size_t>(f[1])] - q[static_cast<std::size_t>(f[0])])
                        .cross(q[static_cast<std::size_t>(f[2])] - q[static_cast<std::size_t>(f[0])])))
        return false;
    }
  for (const auto& ea : kEdges)
    for (const auto& eb : kEdges) {
      const Vec3 da = a[static_cast<std::size_t>(ea[1])] - a[static_cast<std::size_t>(ea[0])];
      const Vec3 db = b[static_cast<std::size_t>(eb[1])] - b[static_cast<std::size_t>(eb[0])];
      if (separates(da.cross(db))) return false;
    }
  return true;
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
  // Grid cells of about the mean box extent, at most ~8 n of them.
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
    return std::clamp(i, 0L, dims[static_cast<std::size_t>(k)] - 1);
  };
  const auto key = [&](long i, long j, long k) { return i + dims[0] * (j + dims[1] * k); };
  // (grid cell, tet) records sorted by cell: the members of a cell are one run.
  std::vector<std::pair<long, std::uint32_t>> recs;
  recs.reserve(n * 4);
  for (std::size_t t = 0; t < n; ++t)
    for (long k = index(boxes[t].lo, 2); k <= index(boxes[t].hi, 2); ++k)
      for (long j = index(boxes[t].lo, 1); j <= index(boxes[t].hi, 1); ++j)
        for (long i = index(boxes[t].lo, 0); i <= index(boxes[t].hi, 0); ++i)
          recs.emplace_back(key(i, j, k), static_cast<std::uint32_t>(t));
  std::sort(recs.begin(), recs.end());
  std::optional<std::pair<std::size_t, std::size_t>> first;
  for (std::size_t r0 = 0; r0 < recs.size();) {
    std::size_t r1 = r0 + 1;
    while (r1 < recs.size() && recs[r1].first == recs[r0].first) ++r1;
    const long cell_key = recs[r0].first;
    for (std::size_t x = r0; x < r1; ++x)
      for (std::size_t y = x + 1; y < r1; ++y) {
        const std::size_t a = recs[x].second, b = recs[y].second;  // a < b: sorted within the run
        const Box& A = boxes[a];
        const Box& B = boxes[b];
        const double tol = kOverlapTolerance * std::max((A.hi - A.lo).norm(), (B.hi - B.lo).norm());
        bool apart = false;
        for (int k = 0; k < 3 && !apart; ++k) apart = std::min(A.hi[k], B.hi[k]) - std::max(A.lo[k], B.lo[k]) <= tol;
        if (apart) continue;
        const Vec3 corner = A.lo.cwiseMax(B.lo);  // test the pair once: in the cell of this corner
        if (key(index(corner, 0), index(corner, 1), index(corner, 2)) != cell_key) continue;
        if (scope == OverlapScope::disjoint_pairs) {
          bool shared = false;
          for (const std::int32_t pa : m.tets[a])
            for (const std::int32_t pb : m.tets[b]) shared = shared || pa == pb;
          if (shared) continue;
        }
        if (tets_overlap(m, a, b) && (!first || std::make_pair(a, b) < *first)) first = std::make_pair(a, b);
      }
    r0 = r1;
  }
  return first;
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
