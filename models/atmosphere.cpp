#include "models/atmosphere.hpp"

namespace navemu {}  // namespace navemu
