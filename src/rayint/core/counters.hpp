#pragma once
// Named counters of a statistics struct (mesh/tet_traversal.hpp TraversalStats,
// mesh/cell_traversal.hpp CellTraversalStats): one list per struct, in the order of the shard
// format, serves its add(), its JSON (report/) and its shard writer and reader.
#include <array>
#include <cstddef>

namespace rayint {

template <class Stats>
struct Counter {
  const char* name;  // as in the JSON
  long Stats::*member;
};

// s += o, counter by counter.
template <class Stats, std::size_t N>
void add_counters(Stats& s, const Stats& o, const std::array<Counter<Stats>, N>& list) {
  for (const Counter<Stats>& c : list) s.*c.member += o.*c.member;
}

}  // namespace rayint
