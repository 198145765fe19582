#pragma once
// The built-in constellations: nominal orbits of each system turned into broadcast records, so
// one code path serves both real navigation files and the built-in sky.

#include <cstdint>
#include <vector>

#include "models/ephemeris.hpp"
#include "core/time.hpp"

namespace navemu {

// Records of the built-in constellations of `systems` (system_bit; GPS alone by default), with
// toe at the systems' own 2-hour boundaries around `t` (from t - 2 h to t + 26 h every 2 h, so
// any scenario date has a fresh set; GLONASS every 30 min). Like the real satellites, each
// slot gets a new upload every 2 h: a new toe/toc and a new issue of data, the same orbit
// parametrised at the new toe, so positions agree across the data set cutover. The data never
// run out (NavData::renews): past t + 26 h each satellite's sets go on as reuploaded()
// continues them (GPS, QZSS, GLONASS), or as the same orbits give them anew (Galileo, BeiDou).
NavData nominal_constellation(GpsTime t, std::uint32_t systems = system_bit(GnssSystem::kGps));

// One system's records as nominal_constellation gives them, into `out` (cleared; its storage
// reused).
//  GPS: the 24 slots of the GPS SPS Performance Standard Table 3.2-1 (epoch 1993-07-01), PRNs 1-24.
//  Galileo: Walker 24/3/1 at 29 599.8 km, 56 deg (Galileo OS SDD), E01-E24.
//  BeiDou: 24 MEO (Walker 24/3/1, 21 528 km, 55 deg), 3 IGSO (C38-C40, 55 deg, crossing 118 E)
//    and 5 GEO (C01-C05 at 140, 80, 110.5, 160, 58.75 E) of BDS-SIS-ICD-B1I 3.0 3.1.
//  QZSS: 3 quasi-zenith orbits (J01-J03) on one ground track centred on 139 E, J07 GEO at 127 E.
//  GLONASS: 24 slots in 3 planes (GLONASS ICD 5.1 3.1) on their frequency channels, a state
//    vector every 30 min, integrated from one nominal orbit.
void nominal_gps(GpsTime t, std::vector<GpsEphemeris>& out);
void nominal_galileo(GpsTime t, std::vector<GalileoEphemeris>& out);
void nominal_beidou(GpsTime t, std::vector<BeidouEphemeris>& out);
void nominal_qzss(GpsTime t, std::vector<GpsEphemeris>& out);
void nominal_glonass(GpsTime t, std::vector<GlonassEphemeris>& out);

}  // namespace navemu
