#include "models/imu_model.hpp"

namespace navemu {}  // namespace navemu
