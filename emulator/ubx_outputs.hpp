#pragma once
// The UBX output messages of a u-blox receiver (u-blox 8 description UBX-13003221 and the F9
// interface description UBX-18010854, "UBX-NAV-*", "UBX-RXM-*"), built from one epoch of the
// receiver model: which messages the part has, the CFG-MSGOUT items that set their rates, and
// how each is filled.

#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "core/nav_data.hpp"
#include "models/receiver.hpp"
#include "models/measurement.hpp"
#include "models/survey_in.hpp"
#include "protocols/gps_lnav.hpp"
#include "protocols/ubx_messages.hpp"

namespace navemu {

// Messages with lists, refilled every epoch (the lists keep their storage, so encoding an epoch
// does not allocate once they have grown).
struct UbxListScratch {
  ubx::NavSvinfo svinfo;
  ubx::NavSat sat;
  ubx::RxmRawx rawx;
  ubx::RxmSfrbx sfrbx;
  ubx::RxmMeasx measx;
  ubx::MonRf rf;
  ubx::NavSig sig;
  ubx::NavOrb orb;
  ubx::MonComms comms;
  ubx::MonIo io;
};

// What the device knows beyond one epoch, for the messages that report it.
struct UbxPortTraffic {
  std::uint32_t rx_bytes = 0, tx_bytes = 0;
  std::uint32_t parsed_bytes = 0;       // received bytes that were part of a message read
  std::array<std::uint16_t, 8> msgs{};  // messages read, by protocol (CFG-PRT mask bit: UBX 0, NMEA 1, RTCM3 5)
};
struct UbxDeviceStatus {
  std::array<UbxPortTraffic, ubx::kNumPorts> ports{};  // by u-blox port ID
  bool jamming_monitor = false;  // CFG-ITFM-ENABLE: jammingState reported (MON-HW, MON-RF)
  // CFG-ITFM-BBTHRESHOLD, -CWTHRESHOLD: J/N above which broadband / CW jamming is "visible"
  // (CFG-ITFM bbThreshold, cwThreshold on the u-blox 8); the part's defaults.
  double itfm_bb_threshold_db = 3.0, itfm_cw_threshold_db = 15.0;
  bool odometer = false;         // CFG-ODO-USE_ODO
  double odo_distance_m = 0.0;   // since the last NAV-RESETODO
  double odo_total_m = 0.0;      // since the last cold start
  std::uint8_t gnss_enabled = 0x01;  // MON-GNSS bits: GPS 0, GLONASS 1, BeiDou 2, Galileo 3
  std::string_view hw_version;   // MON-VER's, for MON-HW3
  std::uint32_t bands = band_bit(Band::kL1);  // the part's bands: the signals RAWX and NAV-SIG list
  SurveyInState svin;            // the time mode's survey-in (NAV-SVIN)
  bool time_only = false;        // the fix is time mode's time-only fix at the held position
  // The navigation output filters (CFG-NAVSPG-OUTFIL_PDOP, _PACC; CFG-NAV5 pDop, pAcc).
  double outfil_pdop = 25.0, outfil_pacc_m = 100.0;
};

struct EpochView;

// One output message: its ID, the middle of its CFG-MSGOUT item names ("UBX_NAV_PVT" in
// CFG-MSGOUT-UBX_NAV_PVT_UART1), which parts have it, and its encoder.
struct UbxOutput {
  ubx::MsgId id;
  std::string_view msgout;
  bool m8, f9;  // on u-blox 8 (protocol < 27) / u-blox F9 (protocol 27+) receivers
  void (*emit)(const EpochView&, std::vector<std::uint8_t>&);
};

// At most 64: emit_ubx_outputs() takes the messages due as one bit each.
inline constexpr std::size_t kMaxUbxOutputs = 64;

// In the order of one epoch's output: raw measurement data first (it is measured before the
// solution), the navigation messages, and NAV-EOE closing the epoch (UBX-NAV-EOE).
std::span<const UbxOutput> ubx_outputs();
const UbxOutput* find_ubx_output(ubx::MsgId id);

// Appends, for the epoch of `fix` and `meas`, the output messages whose bit (their index in
// ubx_outputs()) is set in `due`, in the order of ubx_outputs().
void emit_ubx_outputs(std::uint64_t due, const ReceiverFix& fix, const EpochMeasurements& meas,
                      const NavData& nav, ReceiverMode mode, const UbxDeviceStatus& status,
                      UbxListScratch& lists, std::vector<std::uint8_t>& out);

// Whether a fix is valid: a fix within the navigation output filters' PDOP and 3D accuracy
// masks (ZED-F9P integration manual UBX-18010802 3.1.7.2; UBX-13003221 "Navigation Output
// Filters"). NAV-PVT gnssFixOK, NAV-STATUS/NAV-SOL gpsFixOK and the NMEA validity follow it; an
// RTK solution has no output filters (the same section).
bool within_output_filters(const ReceiverFix& fix, ReceiverMode mode, const UbxDeviceStatus& status);

// The GPS broadcast record of a satellite as IS-GPS-200 subframes 1-3 carry it (RXM-SFRBX,
// AID-EPH).
lnav::LnavEphemeris to_lnav(const GpsEphemeris& e);
// The ionosphere and UTC parameters of subframe 4 page 18 (IS-GPS-200 20.3.3.5.1.6/7) as the
// satellites broadcast them in week `week`: the file's Klobuchar coefficients, UTC(USNO) = GPS
// - `leap_s`, no leap second announced (RXM-SFRBX, AID-HUI).
lnav::LnavIonoUtc broadcast_iono_utc(const NavData& nav, int week, int leap_s);

}  // namespace navemu
