#include "models/solver.hpp"

namespace navemu {}  // namespace navemu
