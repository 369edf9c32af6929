#include "rayint/core/shard.hpp"

#include <boost/uuid/name_generator_sha1.hpp>
#include <boost/uuid/uuid_io.hpp>
#include <cstdlib>
#include <stdexcept>

namespace rayint {

std::string ShardSpec::label() const { return std::to_string(index) + "/" + std::to_string(count); }

ShardSpec parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  auto number = [&](const std::string& s, long& out) {
    if (s.empty() || s.size() > 9 || s.find_first_not_of("0123456789") != std::string::npos) return false;
    out = std::strtol(s.c_str(), nullptr, 10);
    return true;
  };
  ShardSpec s;
  if (slash == std::string::npos || !number(text.substr(0, slash), s.index) ||
      !number(text.substr(slash + 1), s.count) || s.count < 1 || s.index >= s.count)
    throw std::invalid_argument("--shard: expected I/N with 0 <= I < N, got '" + text + "'");
  return s;
}

IndexRange shard_range(std::size_t total, const ShardSpec& s) {
  // floor(total * i / N) without overflow: total = q N + r, so it is q i + floor(r i / N)
  // (r i < N^2 < 1e18 for N < 1e9, which parse_shard allows).
  const auto n = static_cast<std::size_t>(s.count);
  const std::size_t q = total / n, r = total % n;
  const auto at = [&](long i) {
    const auto k = static_cast<std::size_t>(i);
    return q * k + (r * k) / n;
  };
  return {at(s.index), at(s.index + 1)};
}

std::string fingerprint(const std::vector<std::string>& parts) {
  // A fixed namespace UUID for rayint run fingerprints (random, chosen once).
  const boost::uuids::uuid ns = {{0x6b, 0x1f, 0x52, 0x0e, 0x8a, 0x4d, 0x4c, 0x31, 0x9e, 0x07, 0x3d,
                                  0x55, 0xa2, 0x90, 0x14, 0xc8}};
  std::string joined;
  for (const auto& p : parts) joined += std::to_string(p.size()) + ":" + p + ";";
  boost::uuids::name_generator_sha1 gen(ns);
  return boost::uuids::to_string(gen(joined));
}

}  // namespace rayint
