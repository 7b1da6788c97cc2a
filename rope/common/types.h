// SPDX-License-Identifier: MIT
#pragma once
// Basic value types shared by the rope modules. Positions in metres, velocities in m/s.

#include <Eigen/Core>
#include <vector>

namespace rope {

using Vec3 = Eigen::Vector3d;
using PointList = std::vector<Vec3>;

}  // namespace rope
