// The load path rewritten for big meshes (issue 33), checked against brute force: the overlap
// check's candidate grid against every pair, the traversal's face adjacency against a map of
// faces, and the legacy reader's binary decoding of every VTK type (tag [mesh][scaling]).
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

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
