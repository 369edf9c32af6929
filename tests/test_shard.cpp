// Shards and merge (core/shard.hpp, scattering/sample_blocks.hpp, studies/stress.hpp,
// render/mesh_render.hpp): the parts of a run split into shards join to exactly the single
// run -- bit for bit, compared value by value, not within a tolerance -- for the Monte Carlo
// block-sum tree, the slab Monte Carlo, the stress report and a mesh render. The CLI's merge is
// tested end to end by CTest shard_merge_* (tests/shard_merge_test.sh).
#include <catch2/catch.hpp>
#include <cstring>
#include <random>
#include <vector>

#include "rayint/core/shard.hpp"
#include "rayint/integrators/integrator.hpp"
#include "rayint/mesh/mesh_generators.hpp"
#include "rayint/render/mesh_render.hpp"
#include "rayint/report/stress_json.hpp"
#include "rayint/scattering/sample_blocks.hpp"
#include "rayint/scattering/slab_monte_carlo.hpp"
#include "rayint/studies/mesh_agreement.hpp"
#include "mesh_case_fixtures.hpp"
#include "rayint/studies/stress.hpp"

using namespace rayint;

namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool same(const Estimate& a, const Estimate& b) {
  return same_bits(a.mean, b.mean) && same_bits(a.std_error, b.std_error) && a.samples == b.samples;
}

ScoreSums one_score(double x) {
  ScoreSums s(1);
  s.add({x});
  return s;
}

}  // namespace

TEST_CASE("shard I/N parses and the shard ranges partition the items", "[shard]") {
  CHECK(parse_shard("0/1").count == 1);
  CHECK(parse_shard("3/4").index == 3);
  for (const char* bad : {"4/4", "-1/4", "1/0", "1", "a/b", "1/4x", "/4", "1/"})
    CHECK_THROWS_AS(parse_shard(bad), std::invalid_argument);
  for (const std::size_t total : {0u, 1u, 3u, 10u, 1000003u})
    for (const long n : {1L, 2L, 3L, 7L, 64L}) {
      std::size_t next = 0;
      for (long i = 0; i < n; ++i) {
        const IndexRange r = shard_range(total, ShardSpec{i, n});
        CHECK(r.begin == next);
        CHECK(r.size() <= total / static_cast<std::size_t>(n) + 1);
        next = r.end;
      }
      CHECK(next == total);
    }
}

TEST_CASE("block-sum tree: the pairwise order, and any split into shards gives the same root", "[shard]") {
  // Five blocks: ((b0 + b1) + (b2 + b3)) + b4, written out by hand; values chosen so that the
  // left-to-right sum rounds differently.
  const std::vector<double> b = {1.0, 1e-16, 1e-16, 1e-16, 0.5};
  const double by_hand = ((b[0] + b[1]) + (b[2] + b[3])) + b[4];
  const double fold = (((b[0] + b[1]) + b[2]) + b[3]) + b[4];
  REQUIRE(!same_bits(by_hand, fold));
  BlockSumTree whole(b.size());
  for (std::size_t i = 0; i < b.size(); ++i) whole.insert(0, i, one_score(b[i]));
  whole.reduce();
  REQUIRE(whole.complete());
  CHECK(same_bits(whole.total(1).sums()[0], by_hand));

  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const std::size_t blocks : {1u, 2u, 7u, 64u, 1000u}) {
    std::vector<double> v(blocks);
    for (auto& x : v) x = u(rng) * (u(rng) < 0.1 ? 1e8 : 1.0);
    BlockSumTree one(blocks);
    for (std::size_t i = 0; i < blocks; ++i) one.insert(0, i, one_score(v[i]));
    one.reduce();
    for (const long n : {2L, 3L, 4L, 13L}) {
      BlockSumTree merged(blocks);
      std::size_t nodes = 0;
      for (long s = n - 1; s >= 0; --s) {  // shards in reverse order: order must not matter
        const IndexRange r = shard_range(blocks, ShardSpec{s, n});
        BlockSumTree shard(blocks);
        for (std::size_t i = r.begin; i < r.end; ++i) shard.insert(0, i, one_score(v[i]));
        shard.reduce();
        nodes += shard.nodes().size();
        for (const auto& [key, sums] : shard.nodes()) merged.insert(key.first, key.second, sums);
      }
      merged.reduce();
      INFO("blocks " << blocks << " shards " << n);
      CHECK(merged.complete());
      CHECK(same_bits(merged.total(1).sums()[0], one.total(1).sums()[0]));
      CHECK(same_bits(merged.total(1).sums_of_squares()[0], one.total(1).sums_of_squares()[0]));
      CHECK(nodes <= static_cast<std::size_t>(n) * 2 * 11);  // <= 2 log2(blocks) per shard
    }
  }
}

TEST_CASE("slab Monte Carlo: 4 shards merged equal the single run bit for bit", "[shard][scatter]") {
  SlabProblem p;
  p.tau = 1.0;
  p.albedo = 0.9;
  p.phase = PhaseFunction::henyey_greenstein(0.7);
  p.mu_up = {0.1, 0.5};
  p.mu_down = {0.1, 1.0};
  SlabMonteCarloOptions o;
  o.photons = 50 * kBlockPhotons + 17;  // 51 blocks
  o.seed = 11;
  o.threads = 2;
  const SlabEstimates single = solve_slab_monte_carlo(p, o);
  std::vector<MonteCarloShardIO> shards(4);
  for (long i = 0; i < 4; ++i) {
    shards[static_cast<std::size_t>(i)].shard = ShardSpec{i, 4};
    SlabMonteCarloOptions so = o;
    so.threads = 1;
    so.shard_io = &shards[static_cast<std::size_t>(i)];
    solve_slab_monte_carlo(p, so);
  }
  MonteCarloShardIO replay;
  replay.mode = MonteCarloShardIO::Mode::replay;
  replay.parts.push_back(merge_parts({&shards[2].parts[0], &shards[0].parts[0], &shards[3].parts[0], &shards[1].parts[0]}));
  SlabMonteCarloOptions mo = o;
  mo.shard_io = &replay;
  const SlabEstimates merged = solve_slab_monte_carlo(p, mo);
  CHECK(merged.photons == single.photons);
  CHECK(merged.collisions == single.collisions);
  CHECK(same(merged.flux_up_top, single.flux_up_top));
  CHECK(same(merged.diffuse_down_bottom, single.diffuse_down_bottom));
  CHECK(same(merged.direct_down_bottom, single.direct_down_bottom));
  for (std::size_t d = 0; d < 2; ++d) {
    CHECK(same(merged.intensity_up_top[d], single.intensity_up_top[d]));
    CHECK(same(merged.intensity_down_bottom[d], single.intensity_down_bottom[d]));
  }
  // Overlapping parts are refused.
  CHECK_THROWS_AS(merge_parts({&shards[0].parts[0], &shards[0].parts[0]}), std::invalid_argument);
}

TEST_CASE("stress: 3 shards finished together equal the single run's report", "[shard][stress]") {
  StressOptions opt;
  opt.count = 300;
  opt.seed = 21;
  opt.threads = 2;
  for (const Regime r : stress_regimes())
    if (r != Regime::long_ray) opt.regimes.push_back(r);
  opt.methods = {parse_method_spec("exact"), parse_method_spec("riemann:n=4")};
  const std::string single = to_json(run_stress(opt)).dump();
  std::vector<StressPartial> parts;
  for (long i = 2; i >= 0; --i) {
    StressOptions so = opt;
    so.shard = ShardSpec{i, 3};
    parts.push_back(run_stress_part(so));
  }
  CHECK(to_json(finish_stress(opt, parts)).dump() == single);
  // one part alone is not the run
  CHECK(to_json(finish_stress(opt, {parts[0]})).dump() != single);
}

TEST_CASE("mesh render: bands of rows assembled equal the single render", "[shard][mesh]") {
  const rayint::test::BallRender ball(17);
  MeshRenderSettings settings;
  const MeshRender single = render_mesh(ball.mc, ball.mesh, *ball.exact, ball.riemann.get(), settings);
  std::vector<MeshRenderPart> parts;
  for (long i = 0; i < 4; ++i) {
    settings.shard = ShardSpec{i, 4};
    parts.push_back(mesh_render_part(render_mesh(ball.mc, ball.mesh, *ball.exact, ball.riemann.get(), settings), settings.shard));
  }
  const MeshRender merged = assemble_mesh_render(parts);
  CHECK(merged.image.pixels == single.image.pixels);
  CHECK(merged.compared.pixels == single.compared.pixels);
  CHECK(merged.rel_error == single.rel_error);
  CHECK(same_bits(merged.error.max_rel, single.error.max_rel));
  CHECK(same_bits(merged.error.mean_rel, single.error.mean_rel));
  CHECK(same_bits(merged.error.median_rel, single.error.median_rel));
  CHECK(same_bits(merged.error.p99_rel, single.error.p99_rel));
  CHECK(merged.error.pixels == single.error.pixels);
  CHECK(merged.cost.rays == single.cost.rays);
  CHECK(merged.cost.pieces == single.cost.pieces);
  CHECK(merged.cost.traversal.face_steps == single.cost.traversal.face_steps);
}
