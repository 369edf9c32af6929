#pragma once
// Resource limits on sizes a user or a file sets (docs/limits.md has the table and the reasons).
//
// Each limit is checked BEFORE the memory or time it bounds is taken, and a request above it is
// refused with one line naming the option or field, the value asked for, the limit and the
// environment variable that raises it (InputError, exit 2). A limit's value is its default unless
// its variable is set to a whole number >= 1 (anything else in the variable is refused the same
// way, naming the variable).
#include <cstdint>
#include <string>

namespace rayint::limits {

struct Limit {
  const char* what;  // what is counted, e.g. "bytes of image memory"
  const char* env;   // the variable that overrides the default
  std::uint64_t default_value;
};

// Bytes of pixel memory one render may hold: width x height x 3 channels x 8 bytes, times the
// images it keeps (the image, and with --compare the compared image and the per-pixel error).
// 8 GiB: a 16384 x 16384 render (6 GiB) fits; measured 7.1 GB peak RSS, 1429 s on this machine.
inline constexpr Limit kImageBytes{"bytes of image memory", "RAYINT_MAX_IMAGE_BYTES", 8ull << 30};
// Monte Carlo photons of one slab problem: one block result per 4096 photons is kept.
inline constexpr Limit kPhotons{"photons", "RAYINT_MAX_PHOTONS", 10'000'000'000ull};
// Samples of one stress run (the command's --count, a gate file's stress.count): the work list
// holds an entry a sample. 10^8 is 10^4 times the default count.
inline constexpr Limit kStressSamples{"samples", "RAYINT_MAX_STRESS_COUNT", 100'000'000ull};
// Shards of one run (--shard I/N, a shard file's shard.count): merge keeps a slot per shard.
inline constexpr Limit kShards{"shards", "RAYINT_MAX_SHARDS", 100'000ull};
// Bytes of one input file (a case, scene, mesh, grid, preset, candidate image, ...): a 10M-tet
// binary .vtu is ~0.6 GB, its ASCII legacy .vtk ~1.5 GB; 4 GiB holds them with room.
inline constexpr Limit kInputBytes{"bytes", "RAYINT_MAX_INPUT_BYTES", 4ull << 30};
// Nodes of one imported transfer function (tf import, a case's preset): 32 bytes a node.
inline constexpr Limit kTransferNodes{"nodes", "RAYINT_MAX_TF_NODES", 1'000'000ull};

// The limit in force: the environment variable's value, or the default.
std::uint64_t value(const Limit& limit);

// Throws InputError "<where>: <requested> <what> is above the limit of <value> (<env>=N raises
// it)" when requested > value(limit); `requested` may be any non-negative double (a product of
// sizes computed in double does not overflow). NaN is refused as well.
void check(const Limit& limit, double requested, const std::string& where);

}  // namespace rayint::limits
