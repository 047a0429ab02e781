// Basic numeric types of the engine. Units are SI throughout (m, kg, s, N, J).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace fibrenet {

using Vec3 = Eigen::Vector3d;
using Quat = Eigen::Quaterniond;
using Mat3 = Eigen::Matrix3d;

inline constexpr double kPi = 3.14159265358979323846;

}  // namespace fibrenet
