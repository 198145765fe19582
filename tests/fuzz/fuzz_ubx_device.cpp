// The u-blox device's command side (emulator/ubx_device.hpp): the bytes a client sends (UBX
// frames, NMEA, noise, in any pieces) go through ubx::Parser and the CFG/poll handlers, and the
// configuration they leave must still encode an epoch. Byte 0 picks the profile (bit 0: M8 or
// F9P), the receiver port the bytes arrive on (bits 1..3) and where the input is cut in two; an
// epoch is encoded for every port after each piece. The epoch is one of the receiver model on
// the nominal constellation, so that the answers built from navigation data (AID-EPH/ALM,
// MGA-DBD, RXM-MEASX) have satellites to encode.

#include <cstdint>
#include <string>

#include "core/time.hpp"
#include "emulator/run_config.hpp"
#include "emulator/ubx_device.hpp"
#include "models/constellation.hpp"
#include "models/receiver.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace {

const navemu::GpsTime kT0 = navemu::gps_from_utc(navemu::CalendarTime{2020, 6, 25, 12, 0, 0.0});

navemu::ReceiverFix a_fix(std::int64_t epoch) {
  navemu::ReceiverFix f;
  f.t = kT0.plus_s(0.2 * static_cast<double>(epoch));
  f.fix = navemu::FixType::k3D;
  f.position = navemu::Geodetic{55.7, 12.5, 40.0};
  f.p_ecef_m = navemu::ecef_from_geodetic(f.position);
  f.num_used = 2;
  f.satellites = {{navemu::gps_sat(5), 120.0, 45.0, 44.0, true}, {navemu::gps_sat(12), 300.0, 10.0, 31.0, true}};
  return f;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const navemu::GnssProfile m8 = navemu::load_gnss_profile("ublox-m8");
  static const navemu::GnssProfile f9p = navemu::load_gnss_profile("ublox-f9p");
  static const navemu::NavData nav = navemu::nominal_constellation(kT0);
  static const navemu::EpochMeasurements meas = [] {
    navemu::Receiver rx(nav, navemu::ReceiverParams{});
    navemu::ImuTruth truth;
    truth.position = navemu::Geodetic{55.7, 12.5, 40.0};
    truth.t = kT0;
    rx.update(kT0, &truth);
    return rx.measurements();
  }();
  if (size == 0) return 0;
  navemu::UbxDevice device((data[0] & 1) != 0 ? f9p : m8, navemu::ReceiverMode::kStandalone, nav);
  const auto input = navemu::fuzz::bytes_of(data + 1, size - 1);
  const std::size_t cut = input.empty() ? 0 : data[0] % (input.size() + 1);
  const auto port = static_cast<navemu::ReceiverPort>((data[0] >> 1 & 7) % navemu::kReceiverPorts);
  std::string out;
  for (std::int64_t piece = 0; piece < 2; ++piece) {
    device.receive(piece == 0 ? input.first(cut) : input.subspan(cut), port, out);
    device.update(a_fix(piece), meas, piece);
    for (std::size_t p = 0; p < navemu::kReceiverPorts; ++p) {
      device.encode(static_cast<navemu::ReceiverPort>(p), out);
      (void)device.take_baud_change(static_cast<navemu::ReceiverPort>(p));
    }
  }
  if (device.period_ns() <= 0) navemu::fuzz::fail("the navigation period is not positive");
  return 0;
}
