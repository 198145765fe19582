#pragma once
// The built-in GPS constellation: the nominal 24-slot orbits of the GPS SPS Performance
// Standard turned into broadcast-ephemeris records, so one code path serves both real
// navigation files and the built-in sky.

#include "models/ephemeris.hpp"
#include "core/time.hpp"

namespace navemu {

// Records for every nominal slot, with toe at the GPS hour boundaries around `t`
// (from t - 2 h to t + 26 h every 2 h, so any scenario date has a fresh set). Like the real
// satellites, each slot gets a new upload every 2 h: a new toe/toc and a new IODE/IODC
// (IS-GPS-200 20.3.4.4), the same orbit parametrised at the new toe, so positions agree across
// the data set cutover. The data never run out (NavData::renews): past t + 26 h each slot's
// sets go on as reuploaded() continues them, the same orbit again.
NavData nominal_constellation(GpsTime t);

}  // namespace navemu
