#pragma once
// What a u-blox receiver answers when its aiding data and navigation database are polled:
// UBX-AID-INI/HUI/ALM/EPH/AOP (u-blox 8 description UBX-13003221, the AID messages; not on
// protocol 27+) and the UBX-MGA-DBD dump (u-blox 8, and ZED-F9P interface description
// UBX-18010854 5.12.3). Pure encoders from the latest fix and measurements and the navigation
// data in use.

#include <cstdint>
#include <vector>

#include "core/nav_data.hpp"
#include "models/measurement.hpp"
#include "models/receiver.hpp"

namespace navemu {

// The GPS satellites AID-ALM, AID-EPH and AID-AOP answer a poll of all of them for.
inline constexpr int kAidSatellites = 32;

// AID-INI: the receiver's position (ECEF, cm), GPS time (week, ms and ns of week) and clock
// drift (ns/s) at the latest fix, flagged valid; before the first fix, nothing flagged valid.
void append_aid_ini(const ReceiverFix& fix, const EpochMeasurements& meas, std::vector<std::uint8_t>& out);

// AID-HUI: the health of GPS SV 1..32 (a healthy record in the file near `t`), the UTC and
// Klobuchar parameters the satellites broadcast (as RXM-SFRBX subframe 4 page 18 has them).
void append_aid_hui(const NavData& nav, GpsTime t, std::vector<std::uint8_t>& out);

// AID-ALM of GPS SV `svid` (1..32): the almanac page of the record in use near `t`, its
// reference time the last multiple of 4096 s before t (IS-GPS-200 20.3.3.5.2.2: toa); week 0
// and no words without a record.
void append_aid_alm(int svid, const NavData& nav, GpsTime t, std::vector<std::uint8_t>& out);

// AID-EPH of GPS SV `svid` (1..32): subframes 1-3 of the ephemeris in use when the satellite is
// tracked (the receiver has decoded it); how 0 and no words otherwise.
void append_aid_eph(int svid, const EpochMeasurements& meas, std::vector<std::uint8_t>& out);

// MGA-DBD: the navigation database, one entry per tracked GPS satellite in navemu's own form
// (the data are firmware-specific): data[0] = 1 (GPS LNAV ephemeris), then the satellite's
// 104-byte AID-EPH payload; then the MGA-ACK that ends the dump with the number of entries sent
// (UBX-MGA-DBD, "Poll the Navigation Database").
void append_mga_dbd_dump(const EpochMeasurements& meas, std::vector<std::uint8_t>& out);

}  // namespace navemu
