#include "models/allan.hpp"

namespace navemu {}  // namespace navemu
