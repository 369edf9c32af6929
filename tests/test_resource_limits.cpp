// The named resource limits of core/limits.hpp (docs/limits.md, issue 30): a request above a
// limit is one line naming the place, the value, the limit and the variable that raises it; the
// variable overrides the default and a malformed value is refused naming the variable. And the
// CLI's check that refuses NaN and infinities for every floating-point option (cli/options.hpp).
#include <catch2/catch.hpp>
#include <cstdlib>
#include <string>

#include "../cli/options.hpp"
#include "rayint/core/error.hpp"
#include "rayint/core/limits.hpp"

namespace limits = rayint::limits;

namespace {
// Sets an environment variable for one scope.
struct EnvVar {
  const char* name;
  EnvVar(const char* n, const char* value) : name(n) { ::setenv(n, value, 1); }
  ~EnvVar() { ::unsetenv(name); }
};
}  // namespace

TEST_CASE("A request above a named limit is refused with the value, the limit and the variable",
          "[reliability][limits]") {
  ::unsetenv("RAYINT_MAX_PHOTONS");
  CHECK(limits::value(limits::kPhotons) == 10'000'000'000ull);
  CHECK_NOTHROW(limits::check(limits::kPhotons, 1e10, "--photons"));
  CHECK_THROWS_WITH(limits::check(limits::kPhotons, 1e15, "--photons"),
                    "--photons: 1e+15 photons is above the limit of 1e+10 (RAYINT_MAX_PHOTONS=N raises "
                    "it; docs/limits.md)");
  // NaN is above every limit (it must not pass a comparison that is false both ways).
  CHECK_THROWS_AS(limits::check(limits::kPhotons, std::nan(""), "--photons"), rayint::InputError);
}

TEST_CASE("A limit's variable overrides its default and a malformed value is refused",
          "[reliability][limits]") {
  {
    const EnvVar v("RAYINT_MAX_SHARDS", "8");
    CHECK(limits::value(limits::kShards) == 8);
    CHECK_NOTHROW(limits::check(limits::kShards, 8, "--shard 0/8"));
    CHECK_THROWS_WITH(limits::check(limits::kShards, 9, "--shard 0/9"),
                      "--shard 0/9: 9 shards is above the limit of 8 (RAYINT_MAX_SHARDS=N raises it; docs/limits.md)");
  }
  for (const char* bad : {"0", "-3", "12x", "lots", "99999999999999999999999"}) {
    const EnvVar v("RAYINT_MAX_SHARDS", bad);
    CHECK_THROWS_WITH(limits::value(limits::kShards),
                      std::string("RAYINT_MAX_SHARDS: must be a whole number >= 1, got '") + bad + "'");
  }
}

TEST_CASE("Floating-point options refuse NaN and infinities, and only them", "[reliability][limits]") {
  using rayint::cli::finite_number_error;
  for (const char* bad : {"nan", "NaN", "inf", "-inf", "Infinity", "1e400", "-1e309"})
    CHECK(finite_number_error(bad) == std::string("must be a finite number, got ") + bad);
  for (const char* good : {"0", "-1", "1e308", "1e-400", "0x1p-3", "2.5"}) CHECK(finite_number_error(good).empty());
  // Not a number at all: left to the option's conversion, which names it.
  CHECK(finite_number_error("abc").empty());
  CHECK(finite_number_error("").empty());
}

TEST_CASE("Sign checks of options print the value as typed, not 300 digits", "[reliability][limits]") {
  using rayint::cli::sign_error;
  CHECK(sign_error("-1", false) == "must be > 0, got -1");
  CHECK(sign_error("0", false) == "must be > 0, got 0");
  CHECK(sign_error("0", true).empty());
  CHECK(sign_error("-1e-300", true) == "must be >= 0, got -1e-300");
  CHECK(sign_error("2", false).empty());
}

TEST_CASE("Integer options say what a value must be, not that it could not be converted",
          "[reliability][limits]") {
  using rayint::cli::whole_number_error;
  CHECK(whole_number_error("-1", true) == "must be a whole number >= 0, got -1");
  CHECK(whole_number_error("abc", true) == "must be a whole number >= 0, got abc");
  CHECK(whole_number_error("1.5", false) == "must be a whole number, got 1.5");
  CHECK(whole_number_error("", false) == "must be a whole number, got ");
  CHECK(whole_number_error("-", false) == "must be a whole number, got -");
  CHECK(whole_number_error("-1", false).empty());
  CHECK(whole_number_error("+7", true).empty());
  CHECK(whole_number_error("0", true).empty());
}
