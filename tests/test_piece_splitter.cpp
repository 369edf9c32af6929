// PieceSplitter (model/pieces.hpp, the tabulated splitter every piece integrator uses) against
// append_pieces, the plain splitting it must reproduce bit for bit: random transfer functions
// (few and many breakpoints, constant functions, shared and separate breakpoints) and segments
// that start, end or stay on breakpoints, run backwards, leave the functions' range or have
// zero length.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "rayint/model/pieces.hpp"

using namespace rayint;

namespace {

PiecewiseLinear random_function(std::mt19937_64& rng, int points, const std::vector<double>& shared) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> s = shared;
  while (static_cast<int>(s.size()) < points) s.push_back(u(rng));
  std::sort(s.begin(), s.end());
  s.erase(std::unique(s.begin(), s.end()), s.end());
  PiecewiseLinear f;
  f.scalar = s;
  // Zeros of both signs: -0.0 is a valid value (>= 0), and a constant or an interpolated value
  // that comes back +0.0 instead of a stored -0.0 differs in its bits.
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double r = u(rng);
    f.value.push_back(r < 0.1 ? 0.0 : r < 0.2 ? -0.0 : 3.0 * u(rng));
  }
  return f;
}

TransferFunctions random_tf(std::mt19937_64& rng, int max_points) {
  std::uniform_int_distribution<int> pts(1, max_points);
  const std::vector<double> shared = {0.25, 0.5};
  TransferFunctions tf;
  for (int c = 0; c < kChannels; ++c) {
    tf.density[static_cast<std::size_t>(c)] = random_function(rng, pts(rng), c == 0 ? shared : std::vector<double>{});
    tf.color[static_cast<std::size_t>(c)] = random_function(rng, pts(rng), c == 1 ? shared : std::vector<double>{});
  }
  return tf;
}

// Bit for bit: == would take -0.0 for +0.0.
bool same(const Piece& a, const Piece& b) {
  const auto bits = [](const Piece& p) {
    std::vector<double> d = {p.length, p.scalar_far, p.scalar_exit};
    for (const Rgb* x : {&p.rho_far, &p.rho_exit, &p.kappa_far, &p.kappa_exit}) d.insert(d.end(), x->begin(), x->end());
    return d;
  };
  const std::vector<double> x = bits(a), y = bits(b);
  return std::memcmp(x.data(), y.data(), x.size() * sizeof(double)) == 0;
}

}  // namespace

TEST_CASE("PieceSplitter gives append_pieces' pieces bit for bit", "[splitter]") {
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  long segments = 0, pieces = 0, on_breakpoints = 0, negative_zeros = 0;
  for (int t = 0; t < 60; ++t) {
    TransferFunctions tf = random_tf(rng, t % 2 == 0 ? 3 : 9);  // union of <= 8 and > 8 points
    if (t % 3 == 0) tf.density[1] = tf.density[2] = tf.density[0];  // grey: four functions evaluated
    const std::vector<double> bps = tf.breakpoints();
    const PieceSplitter splitter(tf);
    std::uniform_int_distribution<std::size_t> pick(0, bps.size() - 1);
    for (int i = 0; i < 2000; ++i) {
      const auto any = [&] {
        const double r = u(rng);
        if (r < 0.25) { ++on_breakpoints; return bps[pick(rng)]; }
        if (r < 0.3) return bps[pick(rng)] + (u(rng) - 0.5) * 1e-14;
        return 1.4 * u(rng) - 0.2;  // beyond both ends of every function too
      };
      Segment seg{u(rng) < 0.02 ? 0.0 : 2.0 * u(rng), any(), 0.0};
      seg.scalar_exit = u(rng) < 0.05 ? seg.scalar_far : any();
      std::vector<Piece> expected;
      append_pieces(tf, seg, bps, expected);
      const std::vector<Piece>& got = splitter.pieces(seg);
      REQUIRE(got.size() == expected.size());
      for (std::size_t k = 0; k < got.size(); ++k) REQUIRE(same(got[k], expected[k]));
      for (const Piece& p : expected)
        for (const Rgb* x : {&p.rho_far, &p.rho_exit, &p.kappa_far, &p.kappa_exit})
          for (double v : *x) negative_zeros += v == 0.0 && std::signbit(v);
      std::vector<Piece> appended(1);  // append() keeps what is there
      splitter.append(seg, appended);
      REQUIRE(appended.size() == expected.size() + 1);
      for (std::size_t k = 0; k < expected.size(); ++k) REQUIRE(same(appended[k + 1], expected[k]));
      ++segments;
      pieces += static_cast<long>(got.size());
    }
  }
  CHECK(pieces > segments);          // segments did cross breakpoints
  CHECK(on_breakpoints > 10000);     // and started or ended on them
  CHECK(negative_zeros > 1000);      // and -0.0 came out of append_pieces
}

TEST_CASE("a NaN scalar gives NaN values, and PieceSplitter the pieces append_pieces gives", "[splitter]") {
  // PiecewiseLinear::operator()(NaN) used to index one past its arrays (found 2026-12-03).
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::mt19937_64 rng(11);
  const TransferFunctions tf = random_tf(rng, 5);
  for (const auto& f : tf.density) CHECK(std::isnan(f(nan)));
  for (const auto& f : tf.color) CHECK(std::isnan(f(nan)));
  const std::vector<double> bps = tf.breakpoints();
  const PieceSplitter splitter(tf);
  for (const Segment seg : {Segment{1.0, nan, 0.5}, Segment{1.0, 0.5, nan}, Segment{1.0, nan, nan}}) {
    std::vector<Piece> expected;
    append_pieces(tf, seg, bps, expected);
    const std::vector<Piece>& got = splitter.pieces(seg);
    REQUIRE(got.size() == expected.size());
    for (std::size_t k = 0; k < got.size(); ++k) CHECK(same(got[k], expected[k]));
  }
}

TEST_CASE("PieceSplitter matches append_pieces on scalar spans that overflow", "[splitter]") {
  // Ends near +-DBL_MAX: s_exit - s_far overflows to inf when they lie on both sides of the
  // breakpoints, and append_pieces' fractions are then 0 or NaN; same-side ends give a finite
  // span (where the splitter skips span / span = 1). Pieces must match either way.
  std::mt19937_64 rng(7);
  const TransferFunctions tf = random_tf(rng, 5);
  const std::vector<double> bps = tf.breakpoints();
  const PieceSplitter splitter(tf);
  long checked = 0;
  for (const double a : {-1.7e308, -1e308, 0.3, 1.7e308})
    for (const double b : {-1.7e308, 0.6, 1e308, 1.7e308}) {
      const Segment seg{1.5, a, b};
      std::vector<Piece> expected;
      append_pieces(tf, seg, bps, expected);
      const std::vector<Piece>& got = splitter.pieces(seg);
      REQUIRE(got.size() == expected.size());
      for (std::size_t k = 0; k < got.size(); ++k) REQUIRE(same(got[k], expected[k]));
      ++checked;
    }
  CHECK(checked == 16);
}

TEST_CASE("TransferFunctions::grey is true only for three densities with the same bits", "[splitter]") {
  std::mt19937_64 rng(5);
  TransferFunctions tf = random_tf(rng, 5);
  CHECK_FALSE(tf.grey());  // three independent random densities
  tf.density[1] = tf.density[2] = tf.density[0];
  CHECK(tf.grey());
  TransferFunctions one_value = tf;
  one_value.density[2].value.back() = std::nextafter(one_value.density[2].value.back(), 10.0);
  CHECK_FALSE(one_value.grey());
  TransferFunctions one_point = tf;
  one_point.density[1].scalar.back() = std::nextafter(one_point.density[1].scalar.back(), 10.0);
  CHECK_FALSE(one_point.grey());
  TransferFunctions signed_zero = tf;  // 0.0 == -0.0, but the results' zeros would differ in sign
  signed_zero.density[0].value[0] = 0.0;
  signed_zero.density[1].value[0] = -0.0;
  signed_zero.density[2].value[0] = 0.0;
  CHECK_FALSE(signed_zero.grey());
  TransferFunctions colours_differ = tf;  // only the densities decide
  colours_differ.color[0].value[0] += 1.0;
  CHECK(colours_differ.grey());
}

TEST_CASE("PieceSplitter's channel and grey columns hold append_pieces' pieces bit for bit", "[splitter]") {
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto bits_equal = [](double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; };
  long pieces = 0;
  for (int t = 0; t < 20; ++t) {
    TransferFunctions tf = random_tf(rng, t % 2 == 0 ? 3 : 9);
    tf.density[1] = tf.density[2] = tf.density[0];  // grey, so the grey columns may be asked for
    const std::vector<double> bps = tf.breakpoints();
    const PieceSplitter splitter(tf);
    PieceChannelColumns channels, ray_channels;
    GreyPieceColumns grey, ray_grey;
    std::vector<Piece> expected;
    std::vector<Segment> segments;
    double s_walk = 0.5;
    for (int i = 0; i < 1000; ++i) {
      Segment seg{2.0 * u(rng), 1.4 * u(rng) - 0.2, 1.4 * u(rng) - 0.2};
      if (i >= 500) {  // a ray-like walk: each end near the last, some exactly on a breakpoint
        seg.scalar_far = s_walk + 0.02 * (u(rng) - 0.5);
        s_walk = i % 13 == 0 && !bps.empty() ? bps[static_cast<std::size_t>(i) % bps.size()] : seg.scalar_far + 0.1 * (u(rng) - 0.5);
        seg.scalar_exit = s_walk;
        if (i % 29 == 0) seg.scalar_far = seg.scalar_exit;  // constant scalar
      }
      if (i % 97 == 0) seg.scalar_far = nan;  // the append_pieces fallback
      append_pieces(tf, seg, bps, expected);
      splitter.append(seg, channels);
      splitter.append(seg, grey);
      segments.push_back(seg);
    }
    // The whole sequence at once (the region hint along a ray) gives the same pieces.
    const long channel_count = splitter.append(segments, ray_channels);
    const long grey_count = splitter.append(segments, ray_grey);
    // ... and counts them as a render states it: per segment of length > 0, one more than the
    // breakpoints strictly inside its scalar range (one for a NaN end or a constant scalar),
    // counted here one breakpoint at a time.
    long stated = 0;
    for (const Segment& seg : segments) {
      if (!(seg.length > 0.0)) continue;
      ++stated;
      if (std::isnan(seg.scalar_far) || std::isnan(seg.scalar_exit)) continue;
      const double lo = std::min(seg.scalar_far, seg.scalar_exit), hi = std::max(seg.scalar_far, seg.scalar_exit);
      for (const double b : bps) stated += lo < b && b < hi ? 1 : 0;
    }
    CHECK(channel_count == stated);
    CHECK(grey_count == stated);
    CHECK(stated >= static_cast<long>(expected.size()));
    REQUIRE(grey.size() == expected.size());
    REQUIRE(ray_grey.size() == expected.size());
    REQUIRE(channels.size() == kChannels * expected.size());
    REQUIRE(ray_channels.size() == kChannels * expected.size());
    for (std::size_t k = 0; k < expected.size(); ++k) {
      const Piece& p = expected[k];
      INFO("tf " << t << " piece " << k);
      for (const GreyPieceColumns* g : {&grey, &ray_grey}) {
        CHECK(bits_equal(g->length[k], p.length));
        CHECK(bits_equal(g->rho_far[k], p.rho_far[0]));
        CHECK(bits_equal(g->rho_exit[k], p.rho_exit[0]));
        for (std::size_t c = 0; c < kChannels; ++c) {
          CHECK(bits_equal(g->kappa_far[c][k], p.kappa_far[c]));
          CHECK(bits_equal(g->kappa_exit[c][k], p.kappa_exit[c]));
        }
      }
      for (const PieceChannelColumns* ch : {&channels, &ray_channels})
        for (std::size_t c = 0; c < kChannels; ++c) {
          const std::size_t i = kChannels * k + c;
          CHECK(bits_equal(ch->length[i], p.length));
          CHECK(bits_equal(ch->rho_far[i], p.rho_far[c]));
          CHECK(bits_equal(ch->rho_exit[i], p.rho_exit[c]));
          CHECK(bits_equal(ch->kappa_far[i], p.kappa_far[c]));
          CHECK(bits_equal(ch->kappa_exit[i], p.kappa_exit[c]));
        }
    }
    pieces += static_cast<long>(expected.size());
  }
  CHECK(pieces > 10000);
}

// Both ends of a segment are evaluated in one pass of eight lanes (PieceSplitter::eval), in
// whichever copy of the per-ray append()s the CPU picks (x86-64-v4, AVX2 or the baseline): each
// lane must still give append_pieces' values, for grey and non-grey functions with and without
// jumps, along ray-like sequences whose ends sit on breakpoints, repeat the last exit end bit for
// bit, stay constant or are NaN.
TEST_CASE("PieceSplitter's per-ray appends match append_pieces with jumps, NaN ends and shared ends", "[splitter]") {
  std::mt19937_64 rng(3303);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto bits_equal = [](double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; };
  long pieces = 0, jump_tfs = 0, grey_tfs = 0;
  for (int t = 0; t < 40; ++t) {
    TransferFunctions tf = random_tf(rng, t % 2 == 0 ? 3 : 9);
    if (t % 4 < 2) {  // a jump: one function's inner node stored twice, left value then right value
      PiecewiseLinear& f = t % 8 < 4 ? tf.density[0] : tf.color[static_cast<std::size_t>(t % 3)];
      const std::size_t k = f.scalar.size() / 2;
      f.scalar.insert(f.scalar.begin() + static_cast<std::ptrdiff_t>(k), f.scalar[k]);
      f.value.insert(f.value.begin() + static_cast<std::ptrdiff_t>(k), 3.0 * u(rng));
    }
    if (t % 2 == 0) tf.density[1] = tf.density[2] = tf.density[0];
    jump_tfs += tf.has_jump();
    grey_tfs += tf.grey();
    const std::vector<double> bps = tf.breakpoints();
    const PieceSplitter splitter(tf);
    std::uniform_int_distribution<std::size_t> pick(0, bps.size() - 1);
    std::vector<Segment> segments;
    double s_walk = 0.5;
    for (int i = 0; i < 1500; ++i) {
      Segment seg{u(rng) < 0.02 ? 0.0 : 2.0 * u(rng), s_walk, 0.0};
      const double r = u(rng);
      if (r < 0.6) seg.scalar_far = s_walk;  // the last exit end, bit for bit
      else if (r < 0.8) seg.scalar_far = s_walk + 1e-13 * (u(rng) - 0.5);
      else seg.scalar_far = bps[pick(rng)];
      const double q = u(rng);
      seg.scalar_exit = q < 0.2 ? bps[pick(rng)] : q < 0.25 ? seg.scalar_far : seg.scalar_far + 0.2 * (u(rng) - 0.5);
      if (i % 101 == 0) seg.scalar_far = nan;
      if (i % 103 == 0) seg.scalar_exit = nan;
      if (i % 211 == 0) seg.scalar_exit = 1e300 * (u(rng) - 0.5);  // beyond every function, span huge
      if (!std::isnan(seg.scalar_exit)) s_walk = seg.scalar_exit;
      segments.push_back(seg);
    }
    std::vector<Piece> expected;
    for (const Segment& seg : segments) append_pieces(tf, seg, bps, expected);
    PieceChannelColumns channels;
    splitter.append(segments, channels);
    REQUIRE(channels.size() == kChannels * expected.size());
    GreyPieceColumns grey;
    if (tf.grey()) {
      splitter.append(segments, grey);
      REQUIRE(grey.size() == expected.size());
    }
    for (std::size_t k = 0; k < expected.size(); ++k) {
      const Piece& p = expected[k];
      INFO("tf " << t << " piece " << k);
      for (std::size_t c = 0; c < kChannels; ++c) {
        const std::size_t i = kChannels * k + c;
        REQUIRE(bits_equal(channels.length[i], p.length));
        REQUIRE(bits_equal(channels.rho_far[i], p.rho_far[c]));
        REQUIRE(bits_equal(channels.rho_exit[i], p.rho_exit[c]));
        REQUIRE(bits_equal(channels.kappa_far[i], p.kappa_far[c]));
        REQUIRE(bits_equal(channels.kappa_exit[i], p.kappa_exit[c]));
        if (tf.grey()) {
          REQUIRE(bits_equal(grey.kappa_far[c][k], p.kappa_far[c]));
          REQUIRE(bits_equal(grey.kappa_exit[c][k], p.kappa_exit[c]));
        }
      }
      if (tf.grey()) {
        REQUIRE(bits_equal(grey.length[k], p.length));
        REQUIRE(bits_equal(grey.rho_far[k], p.rho_far[0]));
        REQUIRE(bits_equal(grey.rho_exit[k], p.rho_exit[0]));
      }
    }
    pieces += static_cast<long>(expected.size());
  }
  CHECK(jump_tfs == 20);
  CHECK(grey_tfs == 20);
  CHECK(pieces > 40 * 1500);
}
