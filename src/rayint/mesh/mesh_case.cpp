// Mesh cases as ordinary cases (see mesh_case.hpp).
#include "rayint/mesh/mesh_case.hpp"

namespace rayint {

std::vector<MeshViewRay> evaluation_rays(const MeshCase& mc) {
  if (!mc.rays.empty() || !mc.camera) return mc.rays;
  std::vector<MeshViewRay> out;
  out.reserve(static_cast<std::size_t>(mc.camera->width) * static_cast<std::size_t>(mc.camera->height));
  const CameraRays camera_rays(*mc.camera);  // the camera's frame once, the rays its bits
  for (int y = 0; y < mc.camera->height; ++y)
    for (int x = 0; x < mc.camera->width; ++x) out.push_back({camera_rays.ray_for_pixel(x, y), mc.background});
  return out;
}

Case trace_mesh_case(const MeshCase& mc, const TetTraversal& mesh, TraversalStats* stats) {
  Case c;
  c.name = mc.name;
  c.description = mc.description;
  c.source = mc.source;
  c.transfer = mc.transfer;
  RayTrace trace;
  for (const MeshViewRay& r : evaluation_rays(mc)) {
    mesh.trace(r.ray, trace, stats);
    c.rays.push_back(ray_with_quadratic_chords(trace, r.background));  // tet10: quadratic chords
  }
  return c;
}

}  // namespace rayint
