#include "models/time.hpp"

namespace navemu {}  // namespace navemu
