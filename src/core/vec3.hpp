#pragma once
// 3-vector type used everywhere (Eigen, unaligned fixed size: safe in std::vector).
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace invasim {
using Vec3 = Eigen::Vector3d;
using Vec3i = Eigen::Vector3i;
using Mat3 = Eigen::Matrix3d;
}  // namespace invasim
