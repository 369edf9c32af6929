#pragma once
// Monte Carlo estimates with their statistical error, and the random streams behind them.
//
// Estimate: the sample mean of n independent scores, its standard error s/sqrt(n) (s the
// unbiased sample standard deviation) and the normal-approximation 95% interval
// mean +- 1.96 SE. ScoreSums accumulates sum and sum of squares per score; sums of disjoint
// sample blocks are added in block order, so a result never depends on how blocks were spread
// over threads.
//
// Rng: xoshiro256++ (Blackman & Vigna 2019), 2^256 - 1 period, seeded through splitmix64.
// block_rng(seed, block) gives the stream of one sample block: splitmix64 of (seed, block)
// fills the state, so streams are reproducible from (seed, block) alone.
#include <cmath>
#include <cstdint>
#include <cstddef>
#include <utility>
#include <vector>

namespace rayint {

struct Estimate {
  double mean = 0;
  double std_error = 0;  // standard error of the mean
  long long samples = 0;
  double lo95() const { return mean - 1.96 * std_error; }
  double hi95() const { return mean + 1.96 * std_error; }
  bool covers(double x) const { return lo95() <= x && x <= hi95(); }
};

// Per-score sums over a set of samples; samples are added with add(scores) or merged.
class ScoreSums {
 public:
  explicit ScoreSums(std::size_t scores = 0) : sum_(scores, 0.0), sum2_(scores, 0.0) {}
  // Sums as carried by a shard file (sum.size() == sum2.size()).
  ScoreSums(std::vector<double> sum, std::vector<double> sum2, long long n)
      : sum_(std::move(sum)), sum2_(std::move(sum2)), n_(n) {}
  const std::vector<double>& sums() const { return sum_; }
  const std::vector<double>& sums_of_squares() const { return sum2_; }
  std::size_t size() const { return sum_.size(); }
  long long samples() const { return n_; }
  // Scores of one sample (one photon): `score[k]` for estimator k.
  void add(const std::vector<double>& score) {
    for (std::size_t k = 0; k < score.size(); ++k) {
      sum_[k] += score[k];
      sum2_[k] += score[k] * score[k];
    }
    ++n_;
  }
  void merge(const ScoreSums& other) {
    for (std::size_t k = 0; k < sum_.size(); ++k) {
      sum_[k] += other.sum_[k];
      sum2_[k] += other.sum2_[k];
    }
    n_ += other.n_;
  }
  // The estimate of score k, multiplied by `scale` (a normalization such as the incident flux).
  Estimate estimate(std::size_t k, double scale = 1.0) const {
    Estimate e;
    e.samples = n_;
    if (n_ == 0) return e;
    const double n = static_cast<double>(n_);
    const double mean = sum_[k] / n;
    double var = n > 1 ? (sum2_[k] - n * mean * mean) / (n - 1) : 0.0;
    if (var < 0) var = 0;  // rounding when every score is equal
    e.mean = scale * mean;
    e.std_error = std::fabs(scale) * std::sqrt(var / n);
    return e;
  }

 private:
  std::vector<double> sum_, sum2_;
  long long n_ = 0;
};

class Rng {
 public:
  explicit Rng(std::uint64_t seed) {
    for (auto& s : s_) s = splitmix64(seed);
  }
  std::uint64_t next() {
    const std::uint64_t result = rotl(s_[0] + s_[3], 23) + s_[0];
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }
  // Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  // Uniform in (0, 1]: safe under log().
  double uniform_open0() { return 1.0 - uniform(); }

  static std::uint64_t splitmix64(std::uint64_t& x) {
    std::uint64_t z = (x += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t s_[4];
};

// The random stream of sample block `block` under `seed`.
inline Rng block_rng(std::uint64_t seed, std::uint64_t block) {
  std::uint64_t x = seed;
  const std::uint64_t a = Rng::splitmix64(x);
  std::uint64_t y = a ^ (block * 0xd1342543de82ef95ULL + 0x2545f4914f6cdd1dULL);
  return Rng(Rng::splitmix64(y));
}

}  // namespace rayint
