#pragma once
// Lanes of doubles in GCC's vector extension: + - * / are each lane's IEEE operation, exactly as
// in scalar code, a comparison gives a mask of -1 / 0 per lane, and `mask ? a : b` selects per
// lane. V2/M2: two lanes (SSE2, the x86-64 baseline); V4/M4: four lanes (one AVX2 operation in a
// function compiled for AVX2, two SSE2 ones otherwise; keep them inside functions: a 32-byte
// vector passed or returned by value changes the calling convention). Used by the tet walk
// (mesh/tet_traversal.cpp), the piece splitter (model/pieces.cpp) and the render's piece count
// (render/mesh_render.cpp).
#include <cstdint>
#include <cstring>

namespace rayint::lanes {

using V2 = double __attribute__((vector_size(16)));
using M2 = std::int64_t __attribute__((vector_size(16)));
using V4 = double __attribute__((vector_size(32)));
using M4 = std::int64_t __attribute__((vector_size(32)));

// Two lanes from memory of any alignment.
inline V2 load2(const double* p) {
  V2 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline M2 load2(const std::int64_t* p) {
  M2 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

}  // namespace rayint::lanes
