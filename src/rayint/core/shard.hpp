#pragma once
// Shards of one long run (`--shard I/N`, `rayint merge`): shard I of N does exactly its part of
// the one run -- the same seed and count, the same per-sample / per-block seeding -- so the
// merged shards equal the single run figure for figure (README, "Shards and merge").
//
// shard_range(total, s) is the contiguous part [begin, end) of `total` items that shard s owns:
// begin = floor(total * I / N), so the parts are disjoint, cover [0, total) and differ in size
// by at most one. The fingerprint of a run is the SHA-1 name-based UUID (RFC 4122 version 5,
// Boost.Uuid name_generator_sha1) of its canonical parameters and the bytes of its input files:
// shards of different runs, or of a run whose inputs changed, have different fingerprints.
#include <cstddef>
#include <string>
#include <vector>

namespace rayint {

struct ShardSpec {
  long index = 0;  // 0 <= index < count
  long count = 1;  // 1: the whole run
  bool whole() const { return count == 1; }
  std::string label() const;  // "I/N"
};

// Parses "I/N" (0 <= I < N, N >= 1); throws std::invalid_argument naming what is wrong.
ShardSpec parse_shard(const std::string& text);

struct IndexRange {
  std::size_t begin = 0, end = 0;
  std::size_t size() const { return end - begin; }
};
IndexRange shard_range(std::size_t total, const ShardSpec& shard);

// Version-5 UUID (SHA-1) of `parts` joined with their lengths (so ("ab","c") != ("a","bc")).
std::string fingerprint(const std::vector<std::string>& parts);

}  // namespace rayint
