#pragma once
// Three-vectors and 3x3 matrices (Eigen): positions, velocities and rotations in the models,
// positions in file formats (RINEX APPROX POSITION XYZ).

#include <Eigen/Core>

namespace navemu {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

}  // namespace navemu
