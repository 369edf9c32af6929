#pragma once
// The mesh path against a single segment (issue 5 target): on a scalar field that is linear over
// the whole mesh, the ray integral through the mesh (traversal, Eq. 9 and Eq. 13 per cell, one
// segment per cell, `exact`) must equal the `exact` integral of ONE segment from the ray's entry
// into the mesh to its exit, with the analytic field at both ends, to <= 1e-13 relative.
// Used by the test ([mesh], tests/test_mesh_traversal.cpp) and by `rayint mesh-agreement`, so
// the README figure and the test are the same computation.
#include <cstdint>

#include "rayint/model/transfer_function.hpp"

namespace rayint {

struct MeshAgreementOptions {
  int rays = 2000;
  std::uint64_t seed = 2026;
  int n = 3;  // linear-box resolution: 6 (2n)^3 tets, jittered interior (mesh_generators.hpp)
};

struct MeshAgreement {
  long rays = 0;           // rays cast (origins on a sphere of radius 4, aimed into [-1.2,1.2]^3)
  long hits = 0;           // rays that cross the mesh
  long segments = 0;       // cell crossings over all rays
  long tets = 0;
  double max_rel = 0.0;    // largest relative error of the intensity, over rays and channels
  double max_length_abs = 0.0;  // largest error of the total length inside (box edge 2)
  long budget_exhausted = 0;
};

// The transfer functions used (breakpoints inside the field's range, so cells split into pieces).
TransferFunctions agreement_transfer_functions();

MeshAgreement measure_linear_field_agreement(const MeshAgreementOptions& options);

// Robustness of traversal: rays exactly through two random vertices of the structured mesh of the
// unit cube (n^3 cubes, 6 Kuhn tets each: the rays run along edges, in faces and through vertices),
// total length inside against the analytic chord. Rays lying in a boundary plane of the cube are
// skipped (tangent: inside or not is a convention).
struct VertexRayChords {
  long rays = 0;
  long tets = 0;
  double max_length_abs = 0.0;  // cube edge 1
  long zero_length_steps = 0, star_searches = 0, budget_exhausted = 0;
};
VertexRayChords measure_vertex_ray_chords(int n, int rays, std::uint64_t seed);

}  // namespace rayint
