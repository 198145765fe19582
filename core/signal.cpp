#include "core/signal.hpp"

#include <cstdint>

namespace navemu {

namespace {

// GPS satellites of Block IIR-M (L2C) and of Blocks IIF and III (L2C and L5) by the PRN they
// broadcast on and the days they did (modified Julian dates; kOpen: still at the table's last
// update), from the IGS satellite metadata (igs_satellite_metadata.snx, blocks SATELLITE/PRN and
// SATELLITE/IDENTIFIER), state of 2023-12-30. Every other PRN-day is a Block IIA, IIR-A or IIR-B
// satellite: L1 C/A and L2 P(Y) only (IS-GPS-200 3.2.1, 3.3.1.1: L2 CM/CL from Block IIR-M on;
// IS-GPS-705 3.3.1.1: L5 from Block IIF on).
constexpr int kOpen = 99999;
struct GpsModernised {
  std::uint8_t prn;
  int mjd_from, mjd_to;  // [from, to)
  bool l5;               // Block IIF or III
};
constexpr GpsModernised kGpsModernised[] = {
    {1, 54914, 55688, false}, {1, 55758, kOpen, true},    {3, 56959, kOpen, true},
    {4, 57420, 57645, false}, {4, 57759, 57886, false},   {4, 58088, 58390, false},
    {4, 58492, 58677, true},  {4, 58777, kOpen, true},    {5, 55060, kOpen, false},
    {6, 56750, 56783, false}, {6, 56794, kOpen, true},    {7, 54540, kOpen, false},
    {8, 57142, 57205, false}, {8, 57218, kOpen, true},    {9, 56871, kOpen, true},
    {10, 57326, kOpen, true}, {11, 59382, kOpen, true},   {12, 54056, kOpen, false},
    {14, 59158, kOpen, true}, {15, 54390, kOpen, false},  {17, 53639, kOpen, false},
    {18, 58921, kOpen, true}, {23, 59044, kOpen, true},   {24, 55959, 56001, false},
    {24, 56148, 56162, false}, {24, 56204, kOpen, true},  {25, 55344, kOpen, true},
    {26, 57106, kOpen, true}, {27, 56218, 56422, false},  {27, 56427, kOpen, true},
    {28, 59878, 59886, false}, {28, 59975, kOpen, true},  {29, 54454, kOpen, false},
    {30, 56422, 56526, false}, {30, 56645, 56699, false}, {30, 56709, kOpen, true},
    {31, 54003, kOpen, false}, {32, 57423, kOpen, true},
};

// The GPS time scale's origin, 1980-01-06, as a modified Julian date (IS-GPS-200 6.2.4). The
// table's days are UTC days; the 18 s between the scales do not matter at its resolution.
constexpr int kGpsEpochMjd = 44244;

}  // namespace

bool broadcasts(SatId sat, SignalId signal, GpsTime t) {
  switch (sat.system()) {
    case GnssSystem::kGps: {
      const bool l2c = signal.band == '2' && signal.code != 'P' && signal.code != 'W' && signal.code != 'Y';
      const bool l5 = signal.band == '5';
      if (!l2c && !l5) return true;
      const double mjd = kGpsEpochMjd + static_cast<double>(t.ns) / 86400e9;
      for (const GpsModernised& m : kGpsModernised)
        if (m.prn == sat.number() && mjd >= m.mjd_from && mjd < m.mjd_to) return l2c || m.l5;
      return false;
    }
    case GnssSystem::kBeidou:
      // B2I is a BDS-2 signal (BDS-SIS-ICD 2.0, 2013, defines B1I and B2I for BDS-2); BDS-3
      // keeps B1I and B3I (BDS-SIS-ICD-B1I 3.0, -B3I 1.0) and sends B2a/B2b instead of B2I.
      // PRN 1-18 are the BDS-2 satellites' (IGS satellite metadata; BDS-3's start at 19).
      return signal != kBeidouB2I || sat.number() <= 18;
    default: return true;
  }
}

}  // namespace navemu
