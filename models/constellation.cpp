#include "models/constellation.hpp"

namespace navemu {}  // namespace navemu
