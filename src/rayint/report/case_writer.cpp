// case_writer.cpp -- a Case as case-file text (cases/README.md). Numbers go through
// nlohmann::json, which prints the shortest decimal that parses back to the same double, so
// read_case_file(write_case_file(c)) gives c's doubles bit for bit. The layout is compact and
// diff-friendly: each transfer function's points on one line, each segment on one line (a
// 10^4-segment long ray is 10^4 lines, not 10^5).
#include "rayint/report/case_writer.hpp"

#include <stdexcept>

#include "rayint/core/atomic_file.hpp"

namespace rayint {
namespace {

using json = nlohmann::ordered_json;

// A case file holds linear segments only (cases/README.md): a ray with quadratic chords
// (model/ray.hpp, tet10) would be written as another field, so it is not written at all.
void refuse_quadratic(const Case& c) {
  for (const Ray& r : c.rays)
    if (has_quadratic_segments(r))
      throw std::invalid_argument(c.name + ": a ray with quadratic chords (quadratic tetrahedra) has no case-file form");
}

bool same(const PiecewiseLinear& a, const PiecewiseLinear& b) {
  return a.scalar == b.scalar && a.value == b.value;
}

json points(const PiecewiseLinear& f) {
  json out = json::array();
  for (std::size_t k = 0; k < f.scalar.size(); ++k) out.push_back(json::array({f.scalar[k], f.value[k]}));
  return out;
}

json channels(const std::array<PiecewiseLinear, kChannels>& f) {
  if (same(f[0], f[1]) && same(f[0], f[2])) return points(f[0]);
  return json{{"r", points(f[0])}, {"g", points(f[1])}, {"b", points(f[2])}};
}

json segment_json(const Segment& s) {
  return json{{"length", s.length}, {"scalar", json::array({s.scalar_far, s.scalar_exit})}};
}

// `"key": <channels>` at `indent`: the shared form on one line, the per-channel form one
// channel per line.
std::string channels_text(const std::string& key, const json& j, const std::string& indent) {
  std::string out = indent + json(key).dump() + ": ";
  if (j.is_array()) return out + j.dump();
  out += "{\n";
  bool first = true;
  for (const auto& item : j.items()) {
    out += std::string(first ? "" : ",\n") + indent + "  " + json(item.key()).dump() + ": " +
           item.value().dump();
    first = false;
  }
  return out + "\n" + indent + "}";
}

}  // namespace

nlohmann::ordered_json case_json(const Case& c) {
  refuse_quadratic(c);
  json rays = json::array();
  for (const Ray& r : c.rays) {
    json segments = json::array();
    for (const Segment& s : r.segments) segments.push_back(segment_json(s));
    rays.push_back(json{{"background", json::array({r.background[0], r.background[1], r.background[2]})},
                        {"segments", std::move(segments)}});
  }
  json j = json::object();
  j["name"] = c.name;
  j["description"] = c.description;
  j["transfer_function"] = {{"density", channels(c.transfer.density)},
                            {"color", channels(c.transfer.color)}};
  j["rays"] = std::move(rays);
  return j;
}

std::string case_text(const Case& c) {
  refuse_quadratic(c);
  std::string out = "{\n";
  out += "  \"name\": " + json(c.name).dump() + ",\n";
  out += "  \"description\": " + json(c.description).dump() + ",\n";
  out += "  \"transfer_function\": {\n";
  out += channels_text("density", channels(c.transfer.density), "    ") + ",\n";
  out += channels_text("color", channels(c.transfer.color), "    ") + "\n";
  out += "  },\n";
  out += "  \"rays\": [";
  for (std::size_t i = 0; i < c.rays.size(); ++i) {
    const Ray& r = c.rays[i];
    out += std::string(i == 0 ? "\n" : ",\n") + "    {\n";
    out += "      \"background\": " +
           json::array({r.background[0], r.background[1], r.background[2]}).dump() + ",\n";
    out += "      \"segments\": [";
    for (std::size_t k = 0; k < r.segments.size(); ++k)
      out += std::string(k == 0 ? "\n" : ",\n") + "        " + segment_json(r.segments[k]).dump();
    out += r.segments.empty() ? "]\n" : "\n      ]\n";
    out += "    }";
  }
  out += c.rays.empty() ? "]\n" : "\n  ]\n";
  return out + "}\n";
}

void write_case_file(const std::string& path, const Case& c) {
  write_file_atomically(path, case_text(c));
}

}  // namespace rayint
