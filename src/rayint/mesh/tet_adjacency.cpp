// Face adjacency of a tetrahedral mesh (see tet_adjacency.hpp).
#include "rayint/mesh/tet_adjacency.hpp"

#include <algorithm>
#include <limits>

#include "rayint/core/error.hpp"
#include "rayint/core/prefaulted.hpp"

namespace rayint {

Vec3 face_plane(const TetMesh& mesh, const std::array<std::int32_t, 3>& key) {
  const Vec3& a = mesh.points[static_cast<std::size_t>(key[0])];
  return (mesh.points[static_cast<std::size_t>(key[1])] - a).cross(mesh.points[static_cast<std::size_t>(key[2])] - a);
}

std::array<std::int32_t, 3> face_key(const TetMesh& mesh, std::size_t t, std::size_t k) {
  std::array<std::int32_t, 3> key{};
  for (std::size_t j = 0; j < 3; ++j) key[j] = mesh.tets[t][static_cast<std::size_t>(kTetFacePoints[k][j])];
  std::sort(key.begin(), key.end());
  return key;
}

std::array<std::array<std::int32_t, 3>, 4> face_keys(const TetMesh& mesh, std::size_t t) {
  const std::array<std::int32_t, 4>& tet = mesh.tets[t];
  std::array<std::int32_t, 4> s = tet;
  const auto order = [&s](std::size_t i, std::size_t j) {
    if (s[j] < s[i]) std::swap(s[i], s[j]);
  };
  order(0, 1), order(2, 3), order(0, 2), order(1, 3), order(1, 2);  // a sorting network of 4
  std::array<std::array<std::int32_t, 3>, 4> keys{};
  for (std::size_t k = 0; k < 4; ++k) {
    // Removing one copy of tet[k] from the sorted four leaves the other three sorted (also when
    // an index repeats: the multiset is the same).
    const std::size_t drop = s[0] == tet[k] ? 0 : s[1] == tet[k] ? 1 : s[2] == tet[k] ? 2 : 3;
    for (std::size_t j = 0, o = 0; j < 4; ++j)
      if (j != drop) keys[k][o++] = s[j];
  }
  return keys;
}

TetNeighbors tet_neighbors(const TetMesh& mesh, const std::string& source) {
  const std::size_t n = mesh.tets.size();
  if (n > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max() / 4))
    throw InputError(source + ": tets: " + std::to_string(n) + " tetrahedra; at most 2^29 - 1 are supported");
  struct Rec {
    std::array<std::int32_t, 3> key;
    std::int32_t tet_k;  // 4 tet + k: sorts as (tet, k)
  };
  // Sorted by (key, tet_k) without a comparison sort of 4n records (it was ~40% of the load's
  // adjacency time): the records are placed straight into buckets by their lowest point index
  // (a counting sort, in tet order, so tet_k ascends within a bucket), then each bucket (~24
  // records on a tetrahedral mesh) is sorted by (key[1], key[2]) with a stable insertion sort.
  // The order is that of sorting by (key, tet_k): the same faces, cells and errors as before.
  std::vector<std::uint32_t> start(mesh.points.size() + 1, 0);
  // The bucket sizes need only each face's lowest point: with the tet's points sorted
  // s0 <= s1 <= s2 <= s3 (face_keys), the three faces that keep s0 start with it and the one
  // without it starts with s1 (also when points repeat), so s0 and s1 are counted without
  // building the faces (face_keys twice a tet was ~1% of the 105k load; issue 33).
  for (std::size_t t = 0; t < n; ++t) {
    const std::array<std::int32_t, 4>& tet = mesh.tets[t];
    const std::int32_t a = std::min(tet[0], tet[1]), b = std::max(tet[0], tet[1]);
    const std::int32_t c = std::min(tet[2], tet[3]), d = std::max(tet[2], tet[3]);
    const std::int32_t s0 = std::min(a, c), s1 = std::min(std::max(a, c), std::min(b, d));
    start[static_cast<std::size_t>(s0) + 1] += 3;
    ++start[static_cast<std::size_t>(s1) + 1];
  }
  for (std::size_t p = 0; p < mesh.points.size(); ++p) start[p + 1] += start[p];
  std::vector<Rec, PrefaultedAllocator<Rec>> recs(4 * n);
  {
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::size_t t = 0; t < n; ++t) {
      const std::array<std::array<std::int32_t, 3>, 4> keys = face_keys(mesh, t);
      for (std::size_t k = 0; k < 4; ++k)
        recs[fill[static_cast<std::size_t>(keys[k][0])]++] = Rec{keys[k], static_cast<std::int32_t>(4 * t + k)};
    }
  }
  const auto by_rest = [](const Rec& x, const Rec& y) {
    return x.key[1] != y.key[1] ? x.key[1] < y.key[1] : x.key[2] < y.key[2];
  };
  for (std::size_t p = 0; p < mesh.points.size(); ++p) {
    // A point in very many faces (the hub of a fan): a stable sort, not a quadratic one.
    if (start[p + 1] - start[p] > 64) {
      std::stable_sort(recs.begin() + start[p], recs.begin() + start[p + 1], by_rest);
      continue;
    }
    for (std::size_t i = start[p] + 1; i < start[p + 1]; ++i) {
      const Rec r = recs[i];
      std::size_t j = i;
      for (; j > start[p] && by_rest(r, recs[j - 1]); --j) recs[j] = recs[j - 1];
      recs[j] = r;
    }
  }
  std::vector<std::uint32_t>().swap(start);
  // +1 when the face's normal points out of tet t (away from its point k).
  const auto sign_of = [&](const std::array<std::int32_t, 3>& key, const Vec3& normal, std::size_t t, std::size_t k) {
    const Vec3& opposite = mesh.points[static_cast<std::size_t>(mesh.tets[t][k])];
    return normal.dot(opposite - mesh.points[static_cast<std::size_t>(key[0])]) < 0.0 ? 1 : -1;
  };
  TetNeighbors next;  // every entry is written below: its pages prefaulted, then zeroed
  next.reserve(n);
  prefault_capacity(next);
  next.resize(n);
  // Compared by element: std::array's == called memcmp (~2% of the 105k load; issue 33).
  const auto same_face = [](const Rec& x, const Rec& y) {
    return x.key[0] == y.key[0] && x.key[1] == y.key[1] && x.key[2] == y.key[2];
  };
  for (std::size_t i = 0; i < recs.size();) {
    std::size_t j = i + 1;
    while (j < recs.size() && same_face(recs[j], recs[i])) ++j;
    if (j - i > 2)
      throw InputError(source + ": tets[" + std::to_string(recs[i + 2].tet_k / 4) + "]: face (" +
                       std::to_string(recs[i].key[0]) + ", " + std::to_string(recs[i].key[1]) + ", " +
                       std::to_string(recs[i].key[2]) + ") is shared by more than two tetrahedra (also tets[" +
                       std::to_string(recs[i].tet_k / 4) + "] and tets[" + std::to_string(recs[i + 1].tet_k / 4) + "])");
    if (j - i == 2) {
      const Vec3 normal = face_plane(mesh, recs[i].key);
      const std::int32_t a = recs[i].tet_k, b = recs[i + 1].tet_k;
      if (sign_of(recs[i].key, normal, static_cast<std::size_t>(a / 4), static_cast<std::size_t>(a % 4)) ==
          sign_of(recs[i].key, normal, static_cast<std::size_t>(b / 4), static_cast<std::size_t>(b % 4)))
        throw InputError(source + ": tets[" + std::to_string(b / 4) + "]: overlaps tets[" + std::to_string(a / 4) +
                         "] (both lie on the same side of their shared face)");
      next[static_cast<std::size_t>(a / 4)][static_cast<std::size_t>(a % 4)] = b / 4;
      next[static_cast<std::size_t>(b / 4)][static_cast<std::size_t>(b % 4)] = a / 4;
    } else {
      next[static_cast<std::size_t>(recs[i].tet_k / 4)][static_cast<std::size_t>(recs[i].tet_k % 4)] = -1;
    }
    i = j;
  }
  return next;
}

}  // namespace rayint
