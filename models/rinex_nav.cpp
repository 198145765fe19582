#include "models/rinex.hpp"

namespace navemu {}  // namespace navemu
