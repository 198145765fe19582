#include "models/geodesy.hpp"

namespace navemu {}  // namespace navemu
