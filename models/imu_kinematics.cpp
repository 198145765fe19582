#include "models/imu_kinematics.hpp"

namespace navemu {}  // namespace navemu
