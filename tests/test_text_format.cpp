// report/text_format.hpp: appendf, the printf the report tables are written with.
#include <catch2/catch.hpp>
#include <string>

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
