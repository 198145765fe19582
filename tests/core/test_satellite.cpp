// Satellite identities (core/satellite.hpp) against the numbering tables they implement: RINEX
// 3.05 section 3.5 ("Satellite numbers"), the u-blox ZED-F9P interface description
// (UBX-18010854 R04) appendix A "Satellite numbering" (UBX gnssId:svId, UBX svId, NMEA 4.10
// extended and NMEA 4.1 numbering), and the NMEA 0183 4.11 GNSS system IDs.

#include <gtest/gtest.h>

#include <optional>
#include <set>
#include <string>

#include "core/sat_table.hpp"
#include "core/satellite.hpp"

namespace navemu {
namespace {

const SatId kG07 = gps_sat(7);
const SatId kS20(GnssSystem::kSbas, 20);  // PRN 120
const SatId kS51(GnssSystem::kSbas, 51);  // PRN 151
const SatId kS52(GnssSystem::kSbas, 52);  // PRN 152
const SatId kS58(GnssSystem::kSbas, 58);  // PRN 158
const SatId kE01(GnssSystem::kGalileo, 1);
const SatId kE36(GnssSystem::kGalileo, 36);
const SatId kC01(GnssSystem::kBeidou, 1);
const SatId kC05(GnssSystem::kBeidou, 5);
const SatId kC06(GnssSystem::kBeidou, 6);
const SatId kC37(GnssSystem::kBeidou, 37);
const SatId kJ01(GnssSystem::kQzss, 1);  // PRN 193
const SatId kJ05(GnssSystem::kQzss, 5);  // PRN 197
const SatId kR01(GnssSystem::kGlonass, 1);
const SatId kR32(GnssSystem::kGlonass, 32);
const SatId kI01(GnssSystem::kNavic, 1);

// RINEX 3.05 section 3.5: system letters G R E C J S I, two-digit numbers; SBAS PRN - 100,
// QZSS PRN - 192.
TEST(SatId, RinexNames) {
  EXPECT_EQ(kG07.rinex(), "G07");
  EXPECT_EQ(kS20.rinex(), "S20");
  EXPECT_EQ(kE36.rinex(), "E36");
  EXPECT_EQ(kC05.rinex(), "C05");
  EXPECT_EQ(kJ01.rinex(), "J01");
  EXPECT_EQ(kR32.rinex(), "R32");
  EXPECT_EQ(kI01.rinex(), "I01");
  EXPECT_EQ(SatId::from_rinex('G', 7), kG07);
  EXPECT_EQ(SatId::from_rinex('S', 20), kS20);
  EXPECT_EQ(SatId::from_rinex('J', 1), kJ01);
  EXPECT_EQ(SatId::from_rinex('R', 32), kR32);
  EXPECT_EQ(SatId::from_rinex('Q', 1), std::nullopt) << "not a RINEX system letter";
  EXPECT_EQ(SatId::from_rinex('G', 0), std::nullopt);
  EXPECT_EQ(SatId::from_rinex('G', 100), std::nullopt) << "two digits";
  // Any two-digit number of a system is a satellite a file can name; the system defines fewer.
  ASSERT_TRUE(SatId::from_rinex('E', 99).has_value());
  EXPECT_FALSE(SatId::from_rinex('E', 99)->defined());
  EXPECT_TRUE(gps_sat(63).defined()) << "IS-GPS-200 assigns C/A codes to PRN 1-63";
  EXPECT_FALSE(gps_sat(64).defined());
  EXPECT_FALSE(SatId(GnssSystem::kSbas, 19).defined()) << "SBAS starts at PRN 120";
}

// Appendix A, column "UBX gnssId:svId": GPS 0:1-32, SBAS 1:120-158, Galileo 2:1-36,
// BeiDou 3:1-37, QZSS 5:1-5, GLONASS 6:1-32 (NavIC 7, F9 HPG L1L5).
TEST(SatId, UbxGnssIdAndSvId) {
  struct Case {
    SatId sat;
    int gnss_id, sv_id;
  };
  for (const Case& c : {Case{kG07, 0, 7}, Case{kS20, 1, 120}, Case{kS58, 1, 158}, Case{kE36, 2, 36},
                        Case{kC37, 3, 37}, Case{kJ05, 5, 5}, Case{kR01, 6, 1}, Case{kI01, 7, 1}}) {
    SCOPED_TRACE(c.sat.rinex());
    EXPECT_EQ(c.sat.ubx_gnss_id(), c.gnss_id);
    EXPECT_EQ(c.sat.ubx_sv_id(), c.sv_id);
    EXPECT_EQ(SatId::from_ubx(c.gnss_id, c.sv_id), c.sat);
  }
  EXPECT_EQ(SatId::from_ubx(1, 119), std::nullopt);
  EXPECT_EQ(SatId::from_ubx(4, 1), std::nullopt) << "IMES is not a satellite system here";
  EXPECT_EQ(SatId::from_ubx(6, 255), std::nullopt) << "GLONASS slot unknown";
}

// Appendix A, column "UBX svId", the single number of messages without gnssId (NAV-SVINFO):
// Galileo 211-246, BeiDou 159-163 and 33-64, QZSS 193-197, GLONASS 65-96.
TEST(SatId, UbxLegacySvId) {
  EXPECT_EQ(kG07.ubx_legacy_sv_id(), 7);
  EXPECT_EQ(kS20.ubx_legacy_sv_id(), 120);
  EXPECT_EQ(kE01.ubx_legacy_sv_id(), 211);
  EXPECT_EQ(kE36.ubx_legacy_sv_id(), 246);
  EXPECT_EQ(kC01.ubx_legacy_sv_id(), 159);
  EXPECT_EQ(kC05.ubx_legacy_sv_id(), 163);
  EXPECT_EQ(kC06.ubx_legacy_sv_id(), 33);
  EXPECT_EQ(kC37.ubx_legacy_sv_id(), 64);
  EXPECT_EQ(kJ01.ubx_legacy_sv_id(), 193);
  EXPECT_EQ(kJ05.ubx_legacy_sv_id(), 197);
  EXPECT_EQ(kR01.ubx_legacy_sv_id(), 65);
  EXPECT_EQ(kR32.ubx_legacy_sv_id(), 96);
  EXPECT_EQ(kI01.ubx_legacy_sv_id(), std::nullopt);
  EXPECT_EQ(SatId(GnssSystem::kBeidou, 38).ubx_legacy_sv_id(), std::nullopt);
}

// Appendix A, columns "NMEA 2.X-4.0 (extended)" (as NMEA 4.10 sends) and "NMEA 4.1+": GPS 1-32,
// SBAS 33-64 and 152-158, GLONASS 65-96 in both; Galileo 301-336, BeiDou 401-437 and QZSS
// 193-197 extended; Galileo 1-36 and BeiDou 1-37 in 4.1 (with their system ID).
TEST(SatId, NmeaIds) {
  using N = NmeaNumbering;
  for (N n : {N::kV410Extended, N::kV411}) {
    EXPECT_EQ(kG07.nmea_id(n), 7);
    EXPECT_EQ(kS20.nmea_id(n), 33);
    EXPECT_EQ(kS51.nmea_id(n), 64);
    EXPECT_EQ(kS52.nmea_id(n), 152);
    EXPECT_EQ(kS58.nmea_id(n), 158);
    EXPECT_EQ(kR01.nmea_id(n), 65);
    EXPECT_EQ(kR32.nmea_id(n), 96);
  }
  EXPECT_EQ(kE01.nmea_id(N::kV410Extended), 301);
  EXPECT_EQ(kE36.nmea_id(N::kV410Extended), 336);
  EXPECT_EQ(kC01.nmea_id(N::kV410Extended), 401);
  EXPECT_EQ(kC37.nmea_id(N::kV410Extended), 437);
  EXPECT_EQ(kJ01.nmea_id(N::kV410Extended), 193);
  EXPECT_EQ(kJ05.nmea_id(N::kV410Extended), 197);
  EXPECT_EQ(kI01.nmea_id(N::kV410Extended), std::nullopt);
  EXPECT_EQ(kE36.nmea_id(N::kV411), 36);
  EXPECT_EQ(kC37.nmea_id(N::kV411), 37);
  EXPECT_EQ(kJ05.nmea_id(N::kV411), 5);
  EXPECT_EQ(kI01.nmea_id(N::kV411), 1);
  EXPECT_EQ(SatId(GnssSystem::kGalileo, 37).nmea_id(N::kV411), std::nullopt);
}

// NMEA 0183 4.11 GNSS system IDs: 1 GPS, 2 GLONASS, 3 Galileo, 4 BeiDou, 5 QZSS, 6 NavIC;
// SBAS satellites are reported with GPS's.
TEST(SatId, NmeaSystemIds) {
  EXPECT_EQ(kG07.info().nmea_system_id, 1);
  EXPECT_EQ(kS20.info().nmea_system_id, 1);
  EXPECT_EQ(kR01.info().nmea_system_id, 2);
  EXPECT_EQ(kE01.info().nmea_system_id, 3);
  EXPECT_EQ(kC01.info().nmea_system_id, 4);
  EXPECT_EQ(kJ01.info().nmea_system_id, 5);
  EXPECT_EQ(kI01.info().nmea_system_id, 6);
}

// Random streams stay those of the PRN for GPS (seeds keep their meaning), and no two
// satellites share a stream index (so neither the per-band index x 10 + band nor the per-arc
// index x 100000 + arc).
TEST(SatId, StreamIndicesStableAndDistinct) {
  EXPECT_EQ(gps_sat(1).stream_index(), 1);
  EXPECT_EQ(gps_sat(63).stream_index(), 63);
  std::set<int> seen;
  for (const GnssSystemInfo& s : kGnssSystems)
    for (int n = s.first_number; n <= s.last_number; ++n) {
      const int i = SatId(s.system, n).stream_index();
      EXPECT_TRUE(seen.insert(i).second) << SatId(s.system, n).rinex();
    }
  EXPECT_EQ(seen.size(), kDefinedSatellites);
}

// Ordered by system in u-blox's gnssId order, then number, as u-blox lists satellites.
TEST(SatId, Ordering) {
  EXPECT_LT(gps_sat(32), kS20);
  EXPECT_LT(kS58, kE01);
  EXPECT_LT(kE36, kC01);
  EXPECT_LT(kC37, kJ01);
  EXPECT_LT(kJ05, kR01);
  EXPECT_LT(kR32, kI01);
  EXPECT_LT(gps_sat(3), gps_sat(12));
}

}  // namespace
}  // namespace navemu
