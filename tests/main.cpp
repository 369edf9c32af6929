// The tests' main: the same effect registration as the CLI's (cli/main.cpp), then Catch2.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include "rayint/effects/standard_effects.hpp"

int main(int argc, char* argv[]) {
  rayint::register_standard_effects();  // multiple_scattering (scene/effect.hpp)
  return Catch::Session().run(argc, argv);
}
