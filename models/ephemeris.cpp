#include "models/ephemeris.hpp"

namespace navemu {}  // namespace navemu
