#pragma once
// Points and directions in 3-D space: Eigen's fixed-size vector, used by meshes, scenes and
// cameras alike so that geometry code never converts between vector types.
#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products

namespace rayint {

using Vec3 = Eigen::Vector3d;

// A viewing ray: cast from the eye at `origin` along the unit vector `direction`. Light travels
// the other way, from the far end back toward the eye (Williams & Max 1992, Sec. 2).
struct ViewRay {
  Vec3 origin = Vec3::Zero();
  Vec3 direction = Vec3::UnitZ();
};

}  // namespace rayint
