// Signal identities (core/signal.hpp): carrier frequencies against the interface
// specifications (multiples of the 10.23 MHz fundamental for the CDMA signals, GLONASS's
// frequency channels), and UBX and NMEA signal identifiers against the ZED-F9P interface
// description (UBX-18010854 R04) appendix B.

#include <gtest/gtest.h>

#include "core/signal.hpp"

namespace navemu {
namespace {

constexpr double kF0 = 10.23e6;  // GPS fundamental frequency (IS-GPS-200 3.3.1.1)

TEST(Signal, CdmaCarrierFrequencies) {
  // GPS L1 154 f0, L2 120 f0 (IS-GPS-200 3.3.1.1), L5 115 f0 (IS-GPS-705 3.3.1.1).
  EXPECT_EQ(carrier_frequency_hz(kGpsL1CA), 154 * kF0);
  EXPECT_EQ(carrier_frequency_hz(kGpsL2CL), 120 * kF0);
  EXPECT_EQ(carrier_frequency_hz(kGpsL2CM), 120 * kF0);
  EXPECT_EQ(carrier_frequency_hz(kGpsL5Q), 115 * kF0);
  EXPECT_EQ(carrier_frequency_hz(kQzssL5I), 115 * kF0);
  EXPECT_EQ(carrier_frequency_hz(kSbasL1CA), 154 * kF0);
  // Galileo E1 154, E5a 115, E5b 118, E6 125 f0.
  EXPECT_EQ(carrier_frequency_hz(kGalileoE1C), 154 * kF0);
  EXPECT_EQ(carrier_frequency_hz(kGalileoE5aQ), 115 * kF0);
  EXPECT_EQ(carrier_frequency_hz(kGalileoE5bI), 118 * kF0);
  EXPECT_EQ(carrier_frequency_hz(kGalileoE6C), 125 * kF0);
  // BeiDou B1I 1561.098, B2I 1207.14 (118 f0), B3I 1268.52 (124 f0), B1C 154 f0, B2a 115 f0.
  EXPECT_EQ(carrier_frequency_hz(kBeidouB1I), 1561.098e6);
  EXPECT_EQ(carrier_frequency_hz(kBeidouB2I), 118 * kF0);
  EXPECT_EQ(carrier_frequency_hz(kBeidouB3I), 124 * kF0);
  EXPECT_EQ(carrier_frequency_hz(kBeidouB1CPilot), 154 * kF0);
  EXPECT_EQ(carrier_frequency_hz(kBeidouB2aPilot), 115 * kF0);
  EXPECT_EQ(carrier_frequency_hz(kNavicL5A), 115 * kF0);
  EXPECT_EQ(carrier_frequency_hz(SignalId{GnssSystem::kGps, '9', 'X'}), 0.0) << "not a signal";
}

// GLONASS FDMA: L1 1602 + k 0.5625 MHz, L2 1246 + k 0.4375 MHz, k = -7..+6 (GLONASS ICD 5.1,
// 3.3.1.4): the lowest and highest channels at 1598.0625 / 1605.375 and 1242.9375 / 1248.625
// MHz.
TEST(Signal, GlonassFrequencyChannels) {
  EXPECT_EQ(carrier_frequency_hz(kGlonassL1OF), 1602.0e6);
  EXPECT_EQ(carrier_frequency_hz(kGlonassL2OF), 1246.0e6);
  EXPECT_EQ(carrier_frequency_hz(kGlonassL1OF, kGlonassMinChannel), 1598.0625e6);
  EXPECT_EQ(carrier_frequency_hz(kGlonassL1OF, kGlonassMaxChannel), 1605.375e6);
  EXPECT_EQ(carrier_frequency_hz(kGlonassL2OF, kGlonassMinChannel), 1242.9375e6);
  EXPECT_EQ(carrier_frequency_hz(kGlonassL2OF, kGlonassMaxChannel), 1248.625e6);
  // L1 / L2 = 9 / 7 on every channel (the ICD's frequency ratio).
  for (int k = kGlonassMinChannel; k <= kGlonassMaxChannel; ++k)
    EXPECT_DOUBLE_EQ(carrier_frequency_hz(kGlonassL1OF, k) / carrier_frequency_hz(kGlonassL2OF, k),
                     9.0 / 7.0);
  EXPECT_EQ(ubx_freq_id(kGlonassMinChannel), 0);
  EXPECT_EQ(ubx_freq_id(kGlonassMaxChannel), 13);
}

// Appendix B "UBX and NMEA signal identifiers".
TEST(Signal, UbxAndNmeaSignalIds) {
  struct Case {
    SatId sat;
    SignalId sig;
    int ubx, nmea;
  };
  const SatId g(GnssSystem::kGps, 7), e(GnssSystem::kGalileo, 11), c(GnssSystem::kBeidou, 20),
      j(GnssSystem::kQzss, 1), r(GnssSystem::kGlonass, 3);
  for (const Case& k : {Case{g, kGpsL1CA, 0, 1}, Case{g, kGpsL2CL, 3, 6}, Case{g, kGpsL2CM, 4, 5},
                        Case{e, kGalileoE1C, 0, 7}, Case{e, kGalileoE1B, 1, 7},
                        Case{e, kGalileoE5bI, 5, 2}, Case{e, kGalileoE5bQ, 6, 2},
                        Case{c, kBeidouB1I, 0, 1}, Case{c, kBeidouB2I, 2, 3},
                        Case{j, kQzssL1CA, 0, 0}, Case{r, kGlonassL1OF, 0, 1},
                        Case{r, kGlonassL2OF, 2, 3}}) {
    SCOPED_TRACE(k.sat.rinex() + " " + k.sig.rinex_code());
    EXPECT_EQ(ubx_sig_id(k.sat, k.sig), k.ubx);
    ASSERT_NE(signal_info(k.sig), nullptr);
    EXPECT_EQ(signal_info(k.sig)->nmea_signal_id, k.nmea);
  }
  // BeiDou's GEO satellites (PRN 1-5, 59-63) broadcast D2: B1I D2 1, B2I D2 3.
  EXPECT_EQ(ubx_sig_id(SatId(GnssSystem::kBeidou, 1), kBeidouB1I), 1);
  EXPECT_EQ(ubx_sig_id(SatId(GnssSystem::kBeidou, 5), kBeidouB2I), 3);
  EXPECT_EQ(ubx_sig_id(SatId(GnssSystem::kBeidou, 59), kBeidouB1I), 1);
  EXPECT_EQ(ubx_sig_id(SatId(GnssSystem::kBeidou, 6), kBeidouB1I), 0);
  EXPECT_EQ(ubx_sig_id(c, kBeidouB3I), std::nullopt) << "u-blox defines no B3I sigId";
}

// RINEX 3.05 section 5.1 observation codes without their type letter.
TEST(Signal, RinexCodes) {
  EXPECT_EQ(kGpsL1CA.rinex_code(), "1C");
  EXPECT_EQ(kGpsL2CL.rinex_code(), "2L");
  EXPECT_EQ(kGpsL5Q.rinex_code(), "5Q");
  EXPECT_EQ(kGalileoE5bI.rinex_code(), "7I");
  EXPECT_EQ(kBeidouB1I.rinex_code(), "2I");
  EXPECT_EQ(kQzssL1S.rinex_code(), "1Z");
  EXPECT_EQ(kNavicL5A.rinex_code(), "5A");
  // Every table row is a distinct signal of its system.
  for (std::size_t a = 0; a < kSignals.size(); ++a)
    for (std::size_t b = a + 1; b < kSignals.size(); ++b)
      EXPECT_NE(kSignals[a].id, kSignals[b].id) << kSignals[a].name << " / " << kSignals[b].name;
}

}  // namespace
}  // namespace navemu
