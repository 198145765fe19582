#include "models/orbit.hpp"

namespace navemu {}  // namespace navemu
