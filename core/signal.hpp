#pragma once
// Signal identities (../shared/DESIGN.md, "Identities, not integers"): a signal is its system,
// band and code, named as RINEX 3 names them (RINEX 3.05 section 5.1, Tables 4-10: the band is
// the frequency band digit, the code the attribute letter, e.g. GPS "1C" L1 C/A, "2L" L2C (L),
// "5Q" L5 pilot), with its carrier frequency and the identifiers UBX and NMEA give it.

#include <array>
#include <compare>
#include <cstddef>
#include <optional>
#include <string>

#include "core/satellite.hpp"
#include "core/time.hpp"

namespace navemu {

struct SignalId {
  GnssSystem system = GnssSystem::kGps;
  char band = '1';  // RINEX band digit
  char code = 'C';  // RINEX attribute letter

  // "1C": the RINEX observation code without its type letter (C, L, D, S).
  std::string rinex_code() const { return {band, code}; }
  friend constexpr auto operator<=>(const SignalId&, const SignalId&) = default;
};

inline constexpr SignalId kGpsL1CA{GnssSystem::kGps, '1', 'C'};
inline constexpr SignalId kGpsL2CL{GnssSystem::kGps, '2', 'L'};
inline constexpr SignalId kGpsL2CM{GnssSystem::kGps, '2', 'S'};
inline constexpr SignalId kGpsL5I{GnssSystem::kGps, '5', 'I'};
inline constexpr SignalId kGpsL5Q{GnssSystem::kGps, '5', 'Q'};
inline constexpr SignalId kSbasL1CA{GnssSystem::kSbas, '1', 'C'};
inline constexpr SignalId kGalileoE1B{GnssSystem::kGalileo, '1', 'B'};
inline constexpr SignalId kGalileoE1C{GnssSystem::kGalileo, '1', 'C'};
inline constexpr SignalId kGalileoE5aI{GnssSystem::kGalileo, '5', 'I'};
inline constexpr SignalId kGalileoE5aQ{GnssSystem::kGalileo, '5', 'Q'};
inline constexpr SignalId kGalileoE5bI{GnssSystem::kGalileo, '7', 'I'};
inline constexpr SignalId kGalileoE5bQ{GnssSystem::kGalileo, '7', 'Q'};
inline constexpr SignalId kGalileoE6C{GnssSystem::kGalileo, '6', 'C'};
inline constexpr SignalId kBeidouB1I{GnssSystem::kBeidou, '2', 'I'};
inline constexpr SignalId kBeidouB2I{GnssSystem::kBeidou, '7', 'I'};
inline constexpr SignalId kBeidouB3I{GnssSystem::kBeidou, '6', 'I'};
inline constexpr SignalId kBeidouB1CData{GnssSystem::kBeidou, '1', 'D'};
inline constexpr SignalId kBeidouB1CPilot{GnssSystem::kBeidou, '1', 'P'};
inline constexpr SignalId kBeidouB2aData{GnssSystem::kBeidou, '5', 'D'};
inline constexpr SignalId kBeidouB2aPilot{GnssSystem::kBeidou, '5', 'P'};
inline constexpr SignalId kQzssL1CA{GnssSystem::kQzss, '1', 'C'};
inline constexpr SignalId kQzssL1S{GnssSystem::kQzss, '1', 'Z'};
inline constexpr SignalId kQzssL2CM{GnssSystem::kQzss, '2', 'S'};
inline constexpr SignalId kQzssL2CL{GnssSystem::kQzss, '2', 'L'};
inline constexpr SignalId kQzssL5I{GnssSystem::kQzss, '5', 'I'};
inline constexpr SignalId kQzssL5Q{GnssSystem::kQzss, '5', 'Q'};
inline constexpr SignalId kGlonassL1OF{GnssSystem::kGlonass, '1', 'C'};
inline constexpr SignalId kGlonassL2OF{GnssSystem::kGlonass, '2', 'C'};
inline constexpr SignalId kNavicL5A{GnssSystem::kNavic, '5', 'A'};

struct SignalInfo {
  SignalId id;
  const char* name;  // as the u-blox interface descriptions name it
  // Carrier frequency; for GLONASS's frequency division, that of channel k = 0, channel k being
  // carrier_hz + k * channel_step_hz.
  double carrier_hz;
  double channel_step_hz;
  // UBX sigId, -1 when u-blox defines none; for BeiDou B1I and B2I the one of the D1 message
  // (D2: one more; ubx_sig_id below).
  int ubx_sig_id;
  // NMEA 0183 4.11 signal ID (GSV) as u-blox sends it; 0 when not known here.
  int nmea_signal_id;
};

// Carrier frequencies: GPS L1 1575.42 and L2 1227.60 MHz (IS-GPS-200 3.3.1.1), L5 1176.45 MHz
// (IS-GPS-705 3.3.1.1); QZSS as GPS (IS-QZSS-PNT); Galileo E1 1575.42, E5a 1176.45, E5b 1207.14,
// E6 1278.75 MHz (RINEX 3.05 Table 6); BeiDou B1I 1561.098, B2I 1207.14, B3I 1268.52, B1C
// 1575.42, B2a 1176.45 MHz (BDS-SIS-ICD-B1I, -B3I, -B1C, -B2a; RINEX 3.05 Table 9); GLONASS
// L1 1602 + k 0.5625 and L2 1246 + k 0.4375 MHz, k = -7..+6 (GLONASS ICD edition 5.1, 3.3.1.4);
// NavIC L5 1176.45 MHz (RINEX 3.05 Table 10).
// UBX sigId: ZED-F9P interface description UBX-18010854 R04 appendix B "UBX and NMEA signal
// identifiers" (L1, L2, E1, E5b, B1I, B2I) and the F9 HPG L1L5 1.40 interface description
// UBX-23006991, "Signal identifiers" (L5, E5a, B1C, B2a, QZSS L5, NavIC). NMEA signal IDs from
// the same appendix B.
inline constexpr std::array<SignalInfo, 29> kSignals{{
    {kGpsL1CA, "GPS L1C/A", 1575.42e6, 0.0, 0, 1},
    {kGpsL2CL, "GPS L2 CL", 1227.60e6, 0.0, 3, 6},
    {kGpsL2CM, "GPS L2 CM", 1227.60e6, 0.0, 4, 5},
    {kGpsL5I, "GPS L5 I", 1176.45e6, 0.0, 6, 0},
    {kGpsL5Q, "GPS L5 Q", 1176.45e6, 0.0, 7, 0},
    {kSbasL1CA, "SBAS L1C/A", 1575.42e6, 0.0, 0, 1},
    {kGalileoE1C, "Galileo E1 C", 1575.42e6, 0.0, 0, 7},
    {kGalileoE1B, "Galileo E1 B", 1575.42e6, 0.0, 1, 7},
    {kGalileoE5aI, "Galileo E5 aI", 1176.45e6, 0.0, 3, 0},
    {kGalileoE5aQ, "Galileo E5 aQ", 1176.45e6, 0.0, 4, 0},
    {kGalileoE5bI, "Galileo E5 bI", 1207.14e6, 0.0, 5, 2},
    {kGalileoE5bQ, "Galileo E5 bQ", 1207.14e6, 0.0, 6, 2},
    {kGalileoE6C, "Galileo E6 C", 1278.75e6, 0.0, -1, 0},
    {kBeidouB1I, "BeiDou B1I", 1561.098e6, 0.0, 0, 1},
    {kBeidouB2I, "BeiDou B2I", 1207.14e6, 0.0, 2, 3},
    {kBeidouB3I, "BeiDou B3I", 1268.52e6, 0.0, -1, 0},
    {kBeidouB1CPilot, "BeiDou B1 Cp", 1575.42e6, 0.0, 5, 0},
    {kBeidouB1CData, "BeiDou B1 Cd", 1575.42e6, 0.0, 6, 0},
    {kBeidouB2aPilot, "BeiDou B2 ap", 1176.45e6, 0.0, 7, 0},
    {kBeidouB2aData, "BeiDou B2 ad", 1176.45e6, 0.0, 8, 0},
    {kQzssL1CA, "QZSS L1C/A", 1575.42e6, 0.0, 0, 0},
    {kQzssL1S, "QZSS L1S", 1575.42e6, 0.0, 1, 0},
    {kQzssL2CM, "QZSS L2 CM", 1227.60e6, 0.0, 4, 0},
    {kQzssL2CL, "QZSS L2 CL", 1227.60e6, 0.0, 5, 0},
    {kQzssL5I, "QZSS L5 I", 1176.45e6, 0.0, 8, 0},
    {kQzssL5Q, "QZSS L5 Q", 1176.45e6, 0.0, 9, 0},
    {kGlonassL1OF, "GLONASS L1 OF", 1602.0e6, 0.5625e6, 0, 1},
    {kGlonassL2OF, "GLONASS L2 OF", 1246.0e6, 0.4375e6, 2, 3},
    {kNavicL5A, "NavIC L5 A", 1176.45e6, 0.0, 0, 0},
}};

// The GLONASS frequency channels in use (GLONASS ICD edition 5.1, 3.3.1.4).
inline constexpr int kGlonassMinChannel = -7;
inline constexpr int kGlonassMaxChannel = 6;

// The index of the signal's row in kSignals, -1 when it has none. Constant expressions use the
// index rather than a pointer: g++ 12 with -fsanitize=undefined does not fold pointer comparisons.
constexpr int signal_index(SignalId s) {
  for (std::size_t k = 0; k < kSignals.size(); ++k)
    if (kSignals[k].id == s) return static_cast<int>(k);
  return -1;
}

// The signal's row of kSignals, nullptr when it has none.
constexpr const SignalInfo* signal_info(SignalId s) {
  const int k = signal_index(s);
  return k < 0 ? nullptr : &kSignals[static_cast<std::size_t>(k)];
}

// Carrier frequency of a signal in the table; for GLONASS on frequency channel k.
constexpr double carrier_frequency_hz(SignalId s, int glonass_channel = 0) {
  const int k = signal_index(s);
  if (k < 0) return 0.0;
  const SignalInfo& i = kSignals[static_cast<std::size_t>(k)];
  return i.carrier_hz + glonass_channel * i.channel_step_hz;
}

// UBX sigId of a satellite's signal. BeiDou's GEO satellites (PRN 1-5 and 59-63) broadcast the
// D2 navigation message on B1I and B2I (BDS-SIS-ICD-B1I 3.0, 5.1), which u-blox tells apart.
constexpr std::optional<int> ubx_sig_id(SatId sat, SignalId s) {
  const int k = signal_index(s);
  if (k < 0 || kSignals[static_cast<std::size_t>(k)].ubx_sig_id < 0) return std::nullopt;
  const bool d2 = sat.system() == GnssSystem::kBeidou && (s == kBeidouB1I || s == kBeidouB2I) &&
                  (sat.number() <= 5 || sat.number() >= 59);
  return kSignals[static_cast<std::size_t>(k)].ubx_sig_id + (d2 ? 1 : 0);
}

// UBX freqId of a GLONASS frequency channel: k + 7, 0..13 (UBX-RXM-RAWX, UBX-NAV-SIG).
constexpr int ubx_freq_id(int glonass_channel) { return glonass_channel + 7; }

// Whether the satellite broadcasts the signal at time t. Every satellite of a system sends its
// system's signals in kSignals, except GPS L2C (Block IIR-M and later) and L5 (Block IIF and
// later), looked up by PRN and day, and BeiDou B2I (BDS-2 only).
bool broadcasts(SatId sat, SignalId signal, GpsTime t);

}  // namespace navemu
