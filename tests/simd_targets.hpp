#pragma once
// Runs a check once per SIMD target that the binary carries code for and this CPU can run
// (Highway's SupportedAndGeneratedTargets: here AVX3, AVX2, SSE4, SSSE3 and the scalar fallback),
// each in its own Catch2 section named after the target, so that the code paths a user's CPU may
// take (gathers instead of AVX-512's permutes, emulated compressing stores, ...) are tested on
// this AVX-512 machine too. The normal dispatch is restored after each section, even on failure.
#include <catch2/catch.hpp>
#include <cstdint>
#include <hwy/targets.h>

namespace rayint::test {

template <class Check>
void for_each_simd_target(Check&& check) {
  for (const std::int64_t target : hwy::SupportedAndGeneratedTargets()) {
    DYNAMIC_SECTION("SIMD target " << hwy::TargetName(target)) {
      struct Restore {
        ~Restore() { hwy::SetSupportedTargetsForTest(0); }
      } restore;
      hwy::SetSupportedTargetsForTest(target);
      check();
    }
  }
}

}  // namespace rayint::test
