#pragma once
// The built-in GPS constellation: the nominal 24-slot orbits of the GPS SPS Performance
// Standard turned into broadcast-ephemeris records, so one code path serves both real
// navigation files and the built-in sky.

#include "models/ephemeris.hpp"
#include "models/time.hpp"

namespace navemu {

// Records for every nominal slot, with toe at the GPS hour boundaries around `t`
// (from t - 2 h to t + 26 h every 2 h, so any scenario date has a fresh set).
NavData nominal_constellation(GpsTime t);

}  // namespace navemu
