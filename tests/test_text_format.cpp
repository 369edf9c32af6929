// report/text_format.hpp: appendf, the printf the report tables are written with.
#include <catch2/catch.hpp>
#include <string>

#include "rayint/report/gate_lines.hpp"
#include "rayint/report/mesh_render_json.hpp"
#include "rayint/report/text_format.hpp"

TEST_CASE("appendf appends the formatted text, whatever its length", "[report]") {
  std::string out = "head ";
  rayint::appendf(out, "%-6s|%5.2f|%3d\n", "ab", 3.14159, 7);
  CHECK(out == "head ab    | 3.14|  7\n");
  // Longer than any of the fixed line buffers the tables used before (1024 characters).
  const std::string word(3000, 'x');
  rayint::appendf(out, "[%s]", word.c_str());
  CHECK(out.size() == 22 + 3002);
  CHECK(out.substr(22) == "[" + word + "]");
  // An empty format leaves the string as it was.
  const std::string before = out;
  rayint::appendf(out, "%s", "");
  CHECK(out == before);
}

// The summary and progress lines are written with appendf too: a long path or phase is kept whole
// (they were cut at 512 or 1024 characters before).
TEST_CASE("summary and progress lines keep a long heat-map path or phase whole", "[report]") {
  const std::string path = "/tmp/" + std::string(2000, 'd') + "/heat.png";
  const rayint::MeshRenderComparison compare{"riemann", path};
  const std::string line = rayint::comparison_summary(compare, rayint::ErrorSummary{}, "exact");
  CHECK(line.rfind("rayint render: riemann vs exact: ", 0) == 0);
  CHECK(line.size() > path.size());
  CHECK(line.substr(line.size() - path.size() - 1) == path + "\n");

  rayint::GateProgress p;
  p.phase = std::string(1500, 'p');
  p.done = 3;
  p.total = 7;
  p.seconds = 2.0;
  CHECK(rayint::gate_progress_line(p) == "gate: " + p.phase + " 3/7, 2 s\n");
}
