// The load path rewritten for big meshes (issue 33), checked against brute force: the overlap
// check's candidate grid against every pair, the traversal's face adjacency against a map of
// faces, and the legacy reader's binary decoding of every VTK type (tag [mesh][scaling]).
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "rayint/core/error.hpp"
#include "rayint/input/vtk_legacy_reader.hpp"
#include "rayint/mesh/mesh_check.hpp"
#include "rayint/mesh/mesh_generators.hpp"
#include "rayint/mesh/tet_traversal.hpp"
#include "mesh_case_fixtures.hpp"

using namespace rayint;
using rayint::test::concat;

namespace {

// The first overlapping pair (a < b, lexicographically smallest) by testing every pair.
std::optional<std::pair<std::size_t, std::size_t>> brute_force_overlap(const TetMesh& m, OverlapScope scope) {
  for (std::size_t a = 0; a < m.tets.size(); ++a)
    for (std::size_t b = a + 1; b < m.tets.size(); ++b) {
      if (scope == OverlapScope::disjoint_pairs) {
        bool shared = false;
        for (const auto pa : m.tets[a])
          for (const auto pb : m.tets[b]) shared = shared || pa == pb;
        if (shared) continue;
      }
      if (tets_overlap(m, a, b)) return std::make_pair(a, b);
    }
  return std::nullopt;
}

// Two copies of `m`, the second moved by `shift` (an Append of two meshes without shared points).
TetMesh appended(const TetMesh& m, const Vec3& shift) {
  TetMesh out = m;
  const auto n = static_cast<std::int32_t>(m.points.size());
  for (const Vec3& p : m.points) out.points.push_back(p + shift);
  out.scalars.insert(out.scalars.end(), m.scalars.begin(), m.scalars.end());
  for (auto t : m.tets) {
    for (auto& i : t) i += n;
    out.tets.push_back(t);
  }
  return out;
}

// `m` with its points scaled about the origin by `scale`, then moved by `shift`.
TetMesh transformed(TetMesh m, double scale, const Vec3& shift) {
  for (Vec3& p : m.points) p = scale * p + shift;
  return m;
}

void append_be(std::string& out, const void* value, std::size_t width) {
  const auto* p = static_cast<const unsigned char*>(value);
  for (std::size_t i = width; i > 0; --i) out.push_back(static_cast<char>(p[i - 1]));  // host is little-endian
}

}  // namespace

TEST_CASE("overlap check: the candidate grid finds what testing every pair finds", "[mesh][scaling]") {
  const TetMesh box = generate_mesh("linear-box", 3, 7).mesh;  // jittered Kuhn box, 162 tets
  const TetMesh ball = generate_mesh("ball", 2, 1).mesh;      // 384 tets
  std::vector<std::pair<std::string, TetMesh>> meshes{{"box", box}, {"ball", ball}};
  // Shifts from far apart (no overlap) to half a cell (many overlaps), and one exact touch.
  for (const Vec3& shift : {Vec3(3.0, 0.0, 0.0), Vec3(1.0, 0.0, 0.0), Vec3(0.5, 0.13, 0.0), Vec3(0.9, 0.9, 0.95),
                            Vec3(0.05, 0.02, 0.01)})
    meshes.emplace_back("box + shifted box", appended(box, shift));
  meshes.emplace_back("ball + shifted ball", appended(ball, Vec3(1.7, 0.4, -0.3)));
  int overlapping = 0;
  for (const auto& [name, m] : meshes)
    for (const OverlapScope scope : {OverlapScope::all_pairs, OverlapScope::disjoint_pairs}) {
      INFO(name << ", " << m.tets.size() << " tets, scope " << static_cast<int>(scope));
      const auto fast = find_overlapping_tets(m, scope);
      const auto slow = brute_force_overlap(m, scope);
      CHECK(fast == slow);
      if (slow) ++overlapping;
    }
  CHECK(overlapping >= 6);  // the sample has overlapping meshes, in both scopes
  // A touching copy of an unjittered box (shifted by exactly its size along x: the copies share a
  // plane, no volume) is not an overlap; shifted by 0.999 it is.
  const TetMesh cube = structured_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), 2, 2, 2);
  CHECK_FALSE(find_overlapping_tets(appended(cube, Vec3(1.0, 0.0, 0.0)), OverlapScope::disjoint_pairs).has_value());
  CHECK_FALSE(brute_force_overlap(appended(cube, Vec3(1.0, 0.0, 0.0)), OverlapScope::disjoint_pairs).has_value());
  CHECK(find_overlapping_tets(appended(cube, Vec3(0.999, 0.0, 0.0)), OverlapScope::disjoint_pairs).has_value());
}

TEST_CASE("overlap check: the boundary fast path agrees with testing every pair", "[mesh][scaling]") {
  // The lemma of mesh_check.hpp: with the face adjacency checked, no tet with a boundary face
  // overlapping another tet means no two tets overlap. Checked against brute force (every pair)
  // on single meshes, appended copies sharing no points (apart, touching, shifted, nested: a small
  // ball inside a larger one, a tiny ball inside one tet) in both scopes.
  const TetMesh box = generate_mesh("linear-box", 3, 7).mesh;  // 162 tets
  const TetMesh ball = generate_mesh("ball", 2, 1).mesh;      // 384 tets
  const TetMesh ring = generate_mesh("ring", 2, 1).mesh;      // non-convex
  const TetMesh cube = structured_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), 2, 2, 2);
  std::vector<std::pair<std::string, TetMesh>> meshes{{"box", box}, {"ball", ball}, {"ring", ring}, {"cube", cube}};
  for (const Vec3& shift : {Vec3(3.0, 0.0, 0.0), Vec3(0.5, 0.13, 0.0), Vec3(0.05, 0.02, 0.01)})
    meshes.emplace_back("box + shifted box", appended(box, shift));
  meshes.emplace_back("cube + touching cube", appended(cube, Vec3(1.0, 0.0, 0.0)));
  meshes.emplace_back("cube + cube 0.999", appended(cube, Vec3(0.999, 0.0, 0.0)));
  meshes.emplace_back("ball + shifted ball", appended(ball, Vec3(1.7, 0.4, -0.3)));
  meshes.emplace_back("ball + ball inside it", concat(ball, transformed(ball, 0.4, Vec3(0.05, -0.02, 0.03))));
  meshes.emplace_back("ring + small ball", concat(ring, transformed(ball, 0.1, Vec3::Zero())));
  // A tiny ball inside one tet of the box: it meets no boundary face of the box.
  Vec3 c = Vec3::Zero();
  for (const auto i : box.tets[80]) c += 0.25 * box.points[static_cast<std::size_t>(i)];
  meshes.emplace_back("box + tiny ball inside one tet", concat(box, transformed(ball, 1e-3, c)));
  int overlapping = 0, decided_fast = 0;
  for (const auto& [name, m] : meshes) {
    INFO(name << ", " << m.tets.size() << " tets");
    const TetNeighbors next = tet_neighbors(m);
    const bool free = boundary_tets_overlap_free(m, next);
    const auto all = brute_force_overlap(m, OverlapScope::all_pairs);
    if (free) {
      ++decided_fast;
      CHECK_FALSE(all.has_value());  // the lemma: nothing overlaps anywhere
    } else {
      ++overlapping;
    }
    for (const OverlapScope scope : {OverlapScope::all_pairs, OverlapScope::disjoint_pairs})
      CHECK(find_overlapping_tets(m, next, scope) == brute_force_overlap(m, scope));
  }
  CHECK(decided_fast >= 6);  // single meshes, far apart, touching: no full check needed
  CHECK(overlapping >= 6);   // shifted, nested, inside one tet
}

TEST_CASE("overlap check: the boundary fast path with hundreds of boundary tets in one grid cell", "[mesh][scaling]") {
  // The fast path filters a grid cell's members in chunks of 256: 400 small disjoint tets (every
  // face a boundary face) in one corner and one large tet far away (the grid's cells follow the
  // mean box size, so the small ones share a few cells). Then one more small tet overlapping the
  // last small one, or touching it across a face, or sharing its vertex and reaching into it:
  // the fast path's verdict against testing every pair.
  const double s = 1e-3;
  const auto add_tet = [](TetMesh& m, const Vec3& p, double size) {
    const auto i = static_cast<std::int32_t>(m.points.size());
    for (const Vec3& q : {p, Vec3(p + Vec3(size, 0, 0)), Vec3(p + Vec3(0, size, 0)), Vec3(p + Vec3(0, 0, size))}) {
      m.points.push_back(q);
      m.scalars.push_back(1.0);
    }
    m.tets.push_back({i, i + 1, i + 2, i + 3});
  };
  TetMesh base;
  for (int j = 0; j < 20; ++j)
    for (int i = 0; i < 20; ++i) add_tet(base, Vec3(2 * s * i, 2 * s * j, 0), s);
  add_tet(base, Vec3(5, 5, 5), 1.0);
  const Vec3 last(2 * s * 19, 2 * s * 19, 0);
  std::vector<std::pair<std::string, TetMesh>> meshes{{"apart", base}};
  TetMesh over = base, touch = base;
  add_tet(over, last + Vec3(0.3 * s, 0.1 * s, 0.1 * s), s);
  meshes.emplace_back("overlapping the last small tet", over);
  {
    // The mirror image of the last small tet in its face x = last.x, points not shared: the two
    // meet in that face (the same coordinates), no volume.
    const auto i0 = static_cast<std::int32_t>(touch.points.size());
    for (const Vec3& q : {last, Vec3(last + Vec3(0, s, 0)), Vec3(last - Vec3(s, 0, 0)), Vec3(last + Vec3(0, 0, s))}) {
      touch.points.push_back(q);
      touch.scalars.push_back(1.0);
    }
    touch.tets.push_back({i0, i0 + 1, i0 + 2, i0 + 3});
  }
  meshes.emplace_back("touching the last small tet across its face", touch);
  // Sharing the last small tet's first vertex (a point of the mesh) and reaching into it (near
  // that vertex it lies inside the small tet).
  TetMesh shared = base;
  const auto v = static_cast<std::int32_t>(4 * 399);
  const auto i0 = static_cast<std::int32_t>(shared.points.size());
  for (const Vec3& q : {Vec3(last + Vec3(0.5 * s, 0.5 * s, 0.1 * s)), Vec3(last + Vec3(0.5 * s, 0.1 * s, 0.5 * s)),
                        Vec3(last + Vec3(0.1 * s, 0.5 * s, 0.5 * s))}) {
    shared.points.push_back(q);
    shared.scalars.push_back(1.0);
  }
  shared.tets.push_back({v, i0, i0 + 2, i0 + 1});  // positive volume
  meshes.emplace_back("sharing a vertex of the last small tet, inside it", shared);
  int overlapping = 0;
  for (const auto& [name, m] : meshes) {
    INFO(name << ", " << m.tets.size() << " tets");
    const TetNeighbors next = tet_neighbors(m);
    const auto all = brute_force_overlap(m, OverlapScope::all_pairs);
    CHECK(boundary_tets_overlap_free(m, next) == !all.has_value());
    for (const OverlapScope scope : {OverlapScope::all_pairs, OverlapScope::disjoint_pairs})
      CHECK(find_overlapping_tets(m, next, scope) == brute_force_overlap(m, scope));
    if (all) ++overlapping;
  }
  CHECK(overlapping == 2);  // the overlapping copy and the vertex-sharing tet; apart and touching: none
}

namespace {

// A fan of tets around the z axis: the axis points (0, 0, 0) and (0, 0, 1) and ring points at
// angles 0, step, 2 step, ..., n step, one tet per consecutive pair, each on the other side of
// the face it shares with the last. Past 2 pi the fan folds over its start (overlaps that share
// the axis points only); at exactly 2 pi (`close`: the last ring point at the first one's
// coordinates, a point of its own) it touches itself along a face and does not overlap.
TetMesh axis_fan(int n, double step, bool close) {
  TetMesh m;
  const auto add = [&m](const Vec3& p) {
    m.points.push_back(p);
    m.scalars.push_back(p.z());
    return static_cast<std::int32_t>(m.points.size() - 1);
  };
  const std::int32_t a = add(Vec3(0, 0, 0)), b = add(Vec3(0, 0, 1));
  std::vector<std::int32_t> ring;
  for (int i = 0; i <= n; ++i) {
    const double th = step * i;
    ring.push_back(add(close && i == n ? m.points[static_cast<std::size_t>(ring[0])]
                                       : Vec3(std::cos(th), std::sin(th), 0.3 + 0.05 * (i % 3))));
  }
  for (std::size_t i = 0; i + 1 < ring.size(); ++i) m.tets.push_back({a, b, ring[i], ring[i + 1]});
  return m;
}

// A ring of hexahedra (6 tets each) around the z axis, swept over `turns` x 2 pi in `slices` steps
// while rising by `rise` per turn: past one turn its end lies in its start (points not shared);
// at one turn without rise (the last slice at the first one's coordinates, its own points) it
// touches itself along a face.
TetMesh swept_ring(int slices, double turns, double rise) {
  TetMesh m;
  const double r0 = 1.0, r1 = 1.5;
  for (int s = 0; s <= slices; ++s) {
    const double u = static_cast<double>(s) / slices, th = 2 * M_PI * turns * u;
    const double c = s == slices && turns == 1.0 ? 1.0 : std::cos(th), sn = s == slices && turns == 1.0 ? 0.0 : std::sin(th);
    for (const double r : {r0, r1})
      for (const double z : {0.0, 0.4}) {
        m.points.emplace_back(r * c, r * sn, z + rise * turns * u);
        m.scalars.push_back(u);
      }
  }
  // Per slice the hexahedron of points 4 s .. 4 s + 7, in the six Kuhn tets of its cube
  // (corner bits: r, z, slice; each tet a path from corner 0 to corner 7).
  const int perms[6][3] = {{1, 2, 4}, {1, 4, 2}, {2, 1, 4}, {2, 4, 1}, {4, 1, 2}, {4, 2, 1}};
  for (int s = 0; s < slices; ++s) {
    const auto corner = [s](int bits) {
      return static_cast<std::int32_t>(4 * (s + ((bits & 4) ? 1 : 0)) + 2 * ((bits & 1) ? 1 : 0) + ((bits & 2) ? 1 : 0));
    };
    for (const auto& p : perms) {
      const int c1 = p[0], c2 = c1 | p[1];
      m.tets.push_back({corner(0), corner(c1), corner(c2), corner(7)});
    }
  }
  return m;
}

// `m` with every point mapped by `f`.
template <class F>
TetMesh mapped(TetMesh m, F f) {
  for (Vec3& p : m.points) p = f(p);
  return m;
}

}  // namespace

TEST_CASE("overlap check: the sweep direction's faces only, on turned and mirrored meshes, folds and self-touching meshes", "[mesh][scaling]") {
  // The sharper lemma of mesh_check.hpp tests only the boundary faces facing one fixed direction
  // e, against the tets whose boxes meet the face's box. Checked against brute force (every pair,
  // both scopes) on meshes that overlap on one side only, each also turned half way round, a
  // quarter, by a generic rotation and mirrored (inverted tets), so that the faces facing e are
  // each time others: appended and nested copies, a fold at the boundary that shares points (a
  // fan of tets around an edge past 2 pi), a fan closing exactly (touching itself), a ring swept
  // past one turn (its end inside its start, points not shared), a ring touching itself.
  const TetMesh ball = generate_mesh("ball", 2, 1).mesh;  // 384 tets
  const TetMesh cube = structured_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), 3, 2, 2);
  std::vector<std::pair<std::string, TetMesh>> base{
      {"ball", ball},
      {"cube + copy overlapping its +x side by 0.1", appended(cube, Vec3(0.9, 0.05, 0.0))},
      {"cube + copy touching its -y side", appended(cube, Vec3(0.0, -1.0, 0.0))},
      {"cube + small ball inside it near its -z side", concat(cube, transformed(ball, 0.12, Vec3(0.5, 0.5, 0.15)))},
      {"ball + small cube poking out of its -x side", concat(ball, transformed(cube, 0.3, Vec3(-1.1, -0.1, -0.1)))},
      {"fan folding over itself (3 pi)", axis_fan(9, M_PI / 3, false)},
      {"fan closing on itself (2 pi)", axis_fan(6, M_PI / 3, true)},
      {"fan short of a turn", axis_fan(5, M_PI / 3, false)},
      {"ring swept 1.2 turns", swept_ring(12, 1.2, 0.0)},
      {"ring swept 1.2 turns, rising 0.3", swept_ring(12, 1.2, 0.3)},
      {"ring touching itself", swept_ring(10, 1.0, 0.0)},
  };
  const double c = std::cos(0.7), sn = std::sin(0.7), c2 = std::cos(1.9), s2 = std::sin(1.9);
  std::vector<std::pair<std::string, TetMesh>> meshes;
  for (const auto& [name, m] : base) {
    meshes.emplace_back(name, m);
    meshes.emplace_back(name + ", turned half way", mapped(m, [](const Vec3& p) { return Vec3(-p.x(), -p.y(), p.z()); }));
    meshes.emplace_back(name + ", turned a quarter", mapped(m, [](const Vec3& p) { return Vec3(p.z(), p.y(), -p.x()); }));
    meshes.emplace_back(name + ", turned", mapped(m, [&](const Vec3& p) {
                          const Vec3 q(c * p.x() - sn * p.y(), sn * p.x() + c * p.y(), p.z());
                          return Vec3(q.x(), c2 * q.y() - s2 * q.z(), s2 * q.y() + c2 * q.z());
                        }));
    meshes.emplace_back(name + ", mirrored", mapped(m, [](const Vec3& p) { return Vec3(p.x(), p.y(), -p.z()); }));
  }
  int overlapping = 0, point_sharing_only = 0, decided_fast = 0;
  for (const auto& [name, m] : meshes) {
    INFO(name << ", " << m.tets.size() << " tets");
    const TetNeighbors next = tet_neighbors(m);
    const auto all = brute_force_overlap(m, OverlapScope::all_pairs);
    const auto disjoint = brute_force_overlap(m, OverlapScope::disjoint_pairs);
    const bool free = boundary_tets_overlap_free(m, next);
    if (free) {
      ++decided_fast;
      CHECK_FALSE(all.has_value());  // the lemma: nothing overlaps anywhere
    }
    CHECK(find_overlapping_tets(m, next, OverlapScope::all_pairs) == all);
    CHECK(find_overlapping_tets(m, next, OverlapScope::disjoint_pairs) == disjoint);
    if (all) ++overlapping;
    if (all && !disjoint) ++point_sharing_only;
  }
  // Every variant of: the overlapping copy, the small ball, the poking cube, the fold, the two
  // rings swept past a turn (6 x 5); of those the fold shares points only (5); the ball, the
  // touching copy, the closing fan, the short fan and the touching ring pass fast (5 x 5).
  CHECK(overlapping == 30);
  CHECK(point_sharing_only == 5);
  CHECK(decided_fast == 25);
}

TEST_CASE("overlap check: the sweep direction's faces only, on random pairs and triples of tets", "[mesh][scaling]") {
  // Every face of a lone tet is a boundary face and about half of them face e, corner cases of
  // the lemma's faces (a tet with two or three facing faces, its face box the box of all their
  // points). Two or three random tets of positive volume, points in a unit cube (some shared in
  // the triples): the fast path's verdict against testing every pair, which it must equal here.
  std::mt19937 rng(33);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  int overlapping = 0, apart = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    TetMesh m;
    const int n_tets = trial % 3 == 2 ? 3 : 2;
    for (int t = 0; t < n_tets; ++t) {
      Vec3 p[4];
      do {
        for (auto& q : p) q = Vec3(u01(rng), u01(rng), u01(rng)) * (t == 1 ? 0.6 : 1.0);
      } while (std::abs((p[1] - p[0]).cross(p[2] - p[0]).dot(p[3] - p[0])) < 0.02);
      const auto i = static_cast<std::int32_t>(m.points.size());
      for (const auto& q : p) {
        m.points.push_back(q);
        m.scalars.push_back(0.0);
      }
      m.tets.push_back({i, i + 1, i + 2, i + 3});
    }
    if (n_tets == 3) m.tets[2][0] = m.tets[0][1];  // the third shares a point with the first
    bool solid = true;  // no tet of zero volume or a sliver (the lemma's premise)
    for (std::size_t t = 0; t < m.tets.size(); ++t) {
      const TetShape shape = classify_tet(m, t);
      solid = solid && (shape == TetShape::Positive || shape == TetShape::Inverted);
    }
    if (!solid) continue;
    TetNeighbors next;
    try {
      next = tet_neighbors(m);
    } catch (const InputError&) {
      continue;  // two tets on one side of a shared face: outside the lemma's premises
    }
    INFO("trial " << trial);
    const auto all = brute_force_overlap(m, OverlapScope::all_pairs);
    CHECK(boundary_tets_overlap_free(m, next) == !all.has_value());
    for (const OverlapScope scope : {OverlapScope::all_pairs, OverlapScope::disjoint_pairs})
      CHECK(find_overlapping_tets(m, next, scope) == brute_force_overlap(m, scope));
    (all ? overlapping : apart) += 1;
  }
  CHECK(overlapping > 500);
  CHECK(apart > 500);
}

TEST_CASE("traversal adjacency equals a map of sorted faces", "[mesh][scaling]") {
  std::vector<std::pair<std::string, TetMesh>> meshes;
  for (const std::string kind : {"ball", "linear-box", "ring"}) meshes.emplace_back(kind, generate_mesh(kind, 3, 1).mesh);
  {
    // The ball with its most used point renumbered 0: its faces fill one bucket of the
    // adjacency's counting sort past the insertion sort's limit (> 64 records).
    TetMesh hub = generate_mesh("ball", 3, 1).mesh;
    std::vector<int> uses(hub.points.size(), 0);
    for (const auto& t : hub.tets)
      for (const auto i : t) ++uses[static_cast<std::size_t>(i)];
    const auto top = static_cast<std::int32_t>(std::max_element(uses.begin(), uses.end()) - uses.begin());
    REQUIRE(3 * uses[static_cast<std::size_t>(top)] > 64);
    std::swap(hub.points[0], hub.points[static_cast<std::size_t>(top)]);
    std::swap(hub.scalars[0], hub.scalars[static_cast<std::size_t>(top)]);
    for (auto& t : hub.tets)
      for (auto& i : t) i = i == top ? 0 : i == 0 ? top : i;
    meshes.emplace_back("ball, hub point first", hub);
  }
  for (const auto& [kind, m] : meshes) {
    std::map<std::array<std::int32_t, 3>, std::vector<std::pair<std::size_t, int>>> faces;
    for (std::size_t t = 0; t < m.tets.size(); ++t)
      for (int k = 0; k < 4; ++k) {
        std::array<std::int32_t, 3> key{};
        std::size_t j = 0;
        for (int q = 0; q < 4; ++q)
          if (q != k) key[j++] = m.tets[t][static_cast<std::size_t>(q)];
        std::sort(key.begin(), key.end());
        faces[key].emplace_back(t, k);
      }
    const TetTraversal tr(m, kind);
    INFO(kind);
    CHECK(tr.face_count() == faces.size());
    std::size_t boundary = 0;
    for (const auto& [key, users] : faces) {
      REQUIRE(users.size() <= 2);
      if (users.size() == 1) {
        ++boundary;
        CHECK(tr.neighbor(users[0].first, users[0].second) == -1);
      } else {
        CHECK(tr.neighbor(users[0].first, users[0].second) == static_cast<std::int32_t>(users[1].first));
        CHECK(tr.neighbor(users[1].first, users[1].second) == static_cast<std::int32_t>(users[0].first));
      }
    }
    CHECK(tr.boundary_face_count() == boundary);
  }
}

TEST_CASE("legacy reader: binary arrays of every VTK type decode to their values", "[mesh][scaling]") {
  std::string f = "# vtk DataFile Version 3.0\ntypes\nBINARY\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n";
  const double xyz[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  for (const double v : xyz) append_be(f, &v, 8);
  f += "\nCELLS 1 5\n";
  for (const std::int32_t v : {4, 0, 1, 2, 3}) append_be(f, &v, 4);
  f += "\nCELL_TYPES 1\n";
  const std::int32_t tetra = 10;
  append_be(f, &tetra, 4);
  f += "\nPOINT_DATA 4\nFIELD arrays 10\n";
  // Per type: the values written and read back (as doubles, exact for each).
  const double expect[10][4] = {{0, 1, 200, 255},           {-128, -1, 0, 127},   {-32768, -2, 3, 32767},
                                {0, 1, 40000, 65535},       {-2147483647.0 - 1, -5, 6, 2147483647.0},
                                {0, 7, 3000000000.0, 4294967295.0},
                                {-9007199254740992.0, -9, 10, 9007199254740992.0},
                                {0, 11, 1e15, 9007199254740992.0},
                                {-0.5, 0.25, 3.0e38, -1.5e-38}, {-1e300, 0.1, 2.5e-300, 7.0}};
  const char* names[10] = {"unsigned_char", "char", "short", "unsigned_short", "int", "unsigned_int",
                           "vtktypeint64", "vtktypeuint64", "float", "double"};
  for (int a = 0; a < 10; ++a) {
    f += std::string("a") + std::to_string(a) + " 1 4 " + names[a] + "\n";
    for (const double v : expect[a]) {
      switch (a) {
        case 0: { const auto x = static_cast<std::uint8_t>(v); append_be(f, &x, 1); break; }
        case 1: { const auto x = static_cast<std::int8_t>(v); append_be(f, &x, 1); break; }
        case 2: { const auto x = static_cast<std::int16_t>(v); append_be(f, &x, 2); break; }
        case 3: { const auto x = static_cast<std::uint16_t>(v); append_be(f, &x, 2); break; }
        case 4: { const auto x = static_cast<std::int32_t>(v); append_be(f, &x, 4); break; }
        case 5: { const auto x = static_cast<std::uint32_t>(v); append_be(f, &x, 4); break; }
        case 6: { const auto x = static_cast<std::int64_t>(v); append_be(f, &x, 8); break; }
        case 7: { const auto x = static_cast<std::uint64_t>(v); append_be(f, &x, 8); break; }
        case 8: { const auto x = static_cast<float>(v); append_be(f, &x, 4); break; }
        default: append_be(f, &v, 8);
      }
    }
    f += "\n";
  }
  for (int a = 0; a < 10; ++a) {
    INFO(names[a]);
    const TetMesh m = parse_vtk_legacy(f, "types.vtk", {"a" + std::to_string(a)});
    REQUIRE(m.scalars.size() == 4);
    for (std::size_t i = 0; i < 4; ++i)
      CHECK(m.scalars[i] == (a == 8 ? static_cast<double>(static_cast<float>(expect[a][i])) : expect[a][i]));
  }
  const TetMesh m = parse_vtk_legacy(f, "types.vtk", {"a9"});
  REQUIRE(m.points.size() == 4);
  for (std::size_t i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) CHECK(m.points[i][k] == xyz[3 * i + static_cast<std::size_t>(k)]);
  REQUIRE(m.tets.size() == 1);
  CHECK(m.tets[0] == std::array<std::int32_t, 4>{0, 1, 2, 3});
}
