#pragma once
// Independent Monte Carlo sample blocks run in parallel (core/parallel.hpp) and their sums
// reduced over a FIXED PAIRWISE TREE of the blocks. Block b always draws from
// block_rng(seed, b) and always holds the same samples, and every node of the tree is the sum
// of its left and right child in that order, so the total is bit-for-bit the same for any
// thread count (tested in tests/test_scatter_slab.cpp) and for any split of the blocks into
// shards (core/shard.hpp): a shard reduces its blocks as far as the tree allows (at most
// 2 log2(blocks) nodes remain) and `rayint merge` finishes the same tree from the shards' nodes.
//
// The tree: level 0 holds the blocks; node (j, k) covers blocks [k 2^j, (k+1) 2^j) and is
// node (j-1, 2k) merged with node (j-1, 2k+1); a node that covers no block below `blocks` is
// empty, and a node with an empty right child is its left child. The root is (L, 0) with
// 2^L >= blocks. Pairwise summation also rounds less than a running sum (error O(log n) eps).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <functional>
#include <map>
#include <stdexcept>
#include <utility>
#include <vector>

#include "rayint/core/parallel.hpp"
#include "rayint/core/shard.hpp"
#include "rayint/scattering/estimate.hpp"

namespace rayint {

class BlockSumTree {
 public:
  using Key = std::pair<int, std::size_t>;  // (level, index)
  explicit BlockSumTree(std::size_t blocks = 0) : blocks_(blocks) {
    while ((std::size_t{1} << levels_) < blocks_) ++levels_;
  }
  std::size_t blocks() const { return blocks_; }
  // Adds a node (a block is level 0); a node already present is replaced.
  void insert(int level, std::size_t index, ScoreSums sums) { nodes_[{level, index}] = std::move(sums); }
  // Combines siblings bottom-up as far as the nodes present allow.
  void reduce() {
    for (int j = 0; j < levels_; ++j) {
      auto it = nodes_.lower_bound({j, 0});
      while (it != nodes_.end() && it->first.first == j) {
        const std::size_t k = it->first.second;
        if (k % 2 == 1) {  // a right child without its left sibling: wait for it
          ++it;
          continue;
        }
        const auto right = nodes_.find({j, k + 1});
        const bool right_empty = ((k + 1) << j) >= blocks_;
        if (right == nodes_.end() && !right_empty) {
          ++it;
          continue;
        }
        ScoreSums parent = std::move(it->second);
        if (right != nodes_.end()) {
          parent.merge(right->second);
          nodes_.erase(right);
        }
        it = nodes_.erase(it);
        nodes_[{j + 1, k / 2}] = std::move(parent);
      }
    }
  }
  bool complete() const { return nodes_.size() == 1 && nodes_.begin()->first == Key{levels_, 0}; }
  const std::map<Key, ScoreSums>& nodes() const { return nodes_; }
  // The root after reduce() when complete(); otherwise (a partial merge) the nodes present
  // merged in the order of their first block.
  ScoreSums total(std::size_t scores) const {
    if (complete()) return nodes_.begin()->second;
    std::vector<std::pair<std::size_t, const ScoreSums*>> by_first;
    for (const auto& [key, sums] : nodes_) by_first.push_back({key.second << key.first, &sums});
    std::sort(by_first.begin(), by_first.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    ScoreSums out(scores);
    for (const auto& n : by_first) out.merge(*n.second);
    return out;
  }
  // Blocks covered by the nodes present.
  std::size_t covered_blocks() const {
    std::size_t n = 0;
    for (const auto& [key, sums] : nodes_) {
      const std::size_t first = key.second << key.first;
      const std::size_t last = std::min(blocks_, (key.second + 1) << key.first);
      n += last > first ? last - first : 0;
    }
    return n;
  }

 private:
  std::size_t blocks_ = 0;
  int levels_ = 0;
  std::map<Key, ScoreSums> nodes_;
};

// Runs blocks [range.begin, range.end) of `blocks` in parallel and reduces them as far as the
// tree allows. threads = 0: all cores. `run_block(b)` must be thread-safe and depend only on b.
// Rethrows the first exception a block threw.
inline BlockSumTree sum_sample_blocks(std::size_t blocks, IndexRange range, unsigned threads,
                                      const std::function<ScoreSums(std::size_t)>& run_block) {
  std::vector<ScoreSums> results(range.size());
  parallel_for(static_cast<long long>(range.size()), threads, [&](long long i) {
    results[static_cast<std::size_t>(i)] = run_block(range.begin + static_cast<std::size_t>(i));
  });
  BlockSumTree tree(blocks);
  for (std::size_t i = 0; i < results.size(); ++i) tree.insert(0, range.begin + i, std::move(results[i]));
  tree.reduce();
  return tree;
}

// One Monte Carlo solve's share of a sharded run (`--shard I/N`): the tree nodes its blocks
// reduced to, and its counters. A merged part unions the shards' nodes and adds the counters.
struct MonteCarloPart {
  std::size_t blocks = 0;  // of the whole run
  std::size_t scores = 0;
  std::map<BlockSumTree::Key, ScoreSums> nodes;
  long long collisions = 0;
  double seconds = 0;  // wall time, summed over shards
};

// The blocks a part's nodes cover, when they are one contiguous range [begin, end) (a shard's
// part always is: shard_range gives it one); {0, 0} with `contiguous` false otherwise.
struct CoveredBlocks {
  IndexRange range;
  bool contiguous = true;
};
inline CoveredBlocks covered_blocks(const MonteCarloPart& p) {
  CoveredBlocks out;
  if (p.nodes.empty()) return out;
  std::size_t lo = p.blocks, hi = 0, total = 0;
  for (const auto& [key, sums] : p.nodes) {
    const std::size_t first = key.second << key.first;
    const std::size_t last = std::min(p.blocks, (key.second + 1) << key.first);
    if (last <= first) continue;
    lo = std::min(lo, first);
    hi = std::max(hi, last);
    total += last - first;
  }
  if (total == 0) return out;
  out.range = {lo, hi};
  out.contiguous = total == hi - lo;
  return out;
}

// What a Monte Carlo solver does with its block sums when it runs in a shard or a merge:
// record: run only `shard`'s blocks and append its part; replay: run nothing, take the next
// part (merged from every shard) and finish the tree. Solvers called in a fixed order (the
// problems of a benchmark) record and replay their parts in that order.
struct MonteCarloShardIO {
  enum class Mode { record, replay } mode = Mode::record;
  ShardSpec shard;
  std::vector<MonteCarloPart> parts;
  std::size_t next = 0;  // replay: the next part to use
};

// The parts of one solve from several shards as one part (nodes unioned, counters added).
// Throws std::invalid_argument when they disagree on the run's blocks or scores or overlap.
inline MonteCarloPart merge_parts(const std::vector<const MonteCarloPart*>& parts) {
  MonteCarloPart out;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const MonteCarloPart& p = *parts[i];
    if (i == 0) {
      out.blocks = p.blocks;
      out.scores = p.scores;
    } else if (p.blocks != out.blocks || p.scores != out.scores) {
      throw std::invalid_argument("Monte Carlo parts of different runs (blocks or scores differ)");
    }
    for (const auto& [key, sums] : p.nodes)
      if (!out.nodes.emplace(key, sums).second)
        throw std::invalid_argument("Monte Carlo parts overlap");
    out.collisions += p.collisions;
    out.seconds += p.seconds;
  }
  return out;
}

// The sum over a run's `blocks` as `io` asks (null: the whole run here): runs the blocks (all,
// or the shard's), or replays a merged part. `collisions` and `seconds` are set to what the
// blocks counted (`counter`, which run_block increments, read after the run) and took.
inline ScoreSums solve_sample_blocks(std::size_t blocks, std::size_t scores, unsigned threads,
                                     MonteCarloShardIO* io,
                                     const std::function<ScoreSums(std::size_t)>& run_block,
                                     const std::atomic<long long>& counter, long long& collisions,
                                     double& seconds) {
  if (io && io->mode == MonteCarloShardIO::Mode::replay) {
    if (io->next >= io->parts.size()) throw std::invalid_argument("merge: the shards hold fewer Monte Carlo solves than the run");
    const MonteCarloPart& p = io->parts[io->next++];
    if (p.blocks != blocks || p.scores != scores)
      throw std::invalid_argument("merge: a shard's Monte Carlo part does not match the run (blocks or scores)");
    BlockSumTree tree(blocks);
    for (const auto& [key, sums] : p.nodes) tree.insert(key.first, key.second, sums);
    tree.reduce();
    collisions = p.collisions;
    seconds = p.seconds;
    return tree.total(scores);
  }
  const IndexRange range = io ? shard_range(blocks, io->shard) : IndexRange{0, blocks};
  const auto start = std::chrono::steady_clock::now();
  BlockSumTree tree = sum_sample_blocks(blocks, range, threads, run_block);
  seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  collisions = counter.load();
  if (io) {
    MonteCarloPart part;
    part.blocks = blocks;
    part.scores = scores;
    part.nodes = tree.nodes();
    part.collisions = collisions;
    part.seconds = seconds;
    io->parts.push_back(std::move(part));
  }
  return tree.total(scores);
}

}  // namespace rayint
