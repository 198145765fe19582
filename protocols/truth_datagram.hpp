#pragma once
// The truth datagram: one vehicle state per UDP datagram, from a simulator to navemu.
// Two encodings of the same message, both documented in docs/truth-protocol.md:
//
// Binary, version 1, little-endian, fixed 160 bytes:
//   off  size  field
//     0     4  magic "NVTR"
//     4     1  version = 1
//     5     1  reserved, 0
//     6     2  flags (bit 0 time is host UTC, else GPS; bit 1 position ECEF, else geodetic;
//              bit 2 velocity ECEF, else NED; bit 3 attitude roll/pitch/yaw, else quaternion;
//              bit 4 specific force and angular rate present; bit 5 temperature present;
//              bits 6..15 zero)
//     8     4  sequence number (uint32, increments by one per datagram)
//    12     8  time, int64 nanoseconds: since the GPS epoch (GPS time) or since 1970-01-01
//              (host UTC, leap seconds excluded as in CLOCK_REALTIME)
//    20    24  position, 3 x float64: lat_deg, lon_deg, h_m (WGS-84 ellipsoid) or x, y, z m
//    44    24  velocity, 3 x float64: north, east, down or x, y, z, m/s
//    68    32  attitude, 4 x float64: quaternion w, x, y, z of the FRD body frame relative to
//              NED, or roll_deg, pitch_deg, yaw_deg and 0
//   100    24  specific force, body frame, 3 x float64, m/s^2
//   124    24  angular rate w_ib, body frame, 3 x float64, rad/s
//   148     8  temperature, float64, deg C
//   156     4  CRC-32 (IEEE 802.3, as zlib's crc32) of bytes 0..155
//
// JSON lines: one object per datagram (or per line of a stream) with the keys
//   {"seq": 17, "t_gps_ns": ... | "t_unix_ns": ...,
//    "lat_deg","lon_deg","h_m" | "x_m","y_m","z_m",
//    "v_n_mps","v_e_mps","v_d_mps" | "vx_mps","vy_mps","vz_mps",
//    "qw","qx","qy","qz" | "roll_deg","pitch_deg","yaw_deg",
//    optional "f_x_mps2","f_y_mps2","f_z_mps2","w_x_radps","w_y_radps","w_z_radps",
//    optional "temperature_c"}
// Exactly one alternative of each group; numbers as JSON numbers, "seq" and the times as
// integers. An optional "version" key must be 1; unknown keys are ignored, duplicates refused.
// At most 4096 bytes.
//
// Decoding checks the framing only (magic, version, length, CRC, JSON syntax and keys); the
// emulator checks the values (finite, in range, time order). A decoder writes `out` only when
// it returns kOk, never throws and accepts any bytes.

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace navemu::truth_datagram {

inline constexpr std::size_t kBinarySize = 160;
inline constexpr std::uint8_t kVersion = 1;

enum class TimeBase : std::uint8_t { kGps, kHostUtc };
enum class PositionFrame : std::uint8_t { kGeodetic, kEcef };
enum class VelocityFrame : std::uint8_t { kNed, kEcef };
enum class AttitudeForm : std::uint8_t { kQuaternion, kRollPitchYaw };

struct Message {
  std::uint32_t sequence = 0;
  TimeBase time_base = TimeBase::kGps;
  std::int64_t time_ns = 0;
  PositionFrame position_frame = PositionFrame::kGeodetic;
  std::array<double, 3> position{};  // lat_deg, lon_deg, h_m or x, y, z m
  VelocityFrame velocity_frame = VelocityFrame::kNed;
  std::array<double, 3> velocity_mps{};
  AttitudeForm attitude_form = AttitudeForm::kQuaternion;
  std::array<double, 4> attitude{1.0, 0.0, 0.0, 0.0};  // w, x, y, z or roll, pitch, yaw deg, 0
  bool has_rates = false;
  std::array<double, 3> f_body_mps2{};
  std::array<double, 3> w_body_radps{};
  bool has_temperature = false;
  double temperature_c = 0.0;
};

enum class DecodeResult {
  kOk,
  kBadLength,
  kBadMagic,
  kBadVersion,    // another version; or the reserved byte or an undefined flag bit set
  kBadCrc,
  kBadJson,       // not a flat JSON object, a value of the wrong type, or a duplicate key
  kMissingField,  // a required group absent or incomplete, or two alternatives of one given
};
const char* to_string(DecodeResult r);

// CRC-32 (IEEE 802.3, reflected, init and final XOR 0xFFFFFFFF); check value of "123456789"
// is 0xCBF43926.
std::uint32_t crc32(std::span<const std::uint8_t> bytes);

std::array<std::uint8_t, kBinarySize> encode_binary(const Message& m);
DecodeResult decode_binary(std::span<const std::uint8_t> bytes, Message& out);

std::string encode_json(const Message& m);  // one line, no trailing newline
DecodeResult decode_json(std::string_view text, Message& out);

// Either encoding: binary when it starts with the magic, JSON when it starts with '{'.
DecodeResult decode(std::span<const std::uint8_t> bytes, Message& out);

}  // namespace navemu::truth_datagram
