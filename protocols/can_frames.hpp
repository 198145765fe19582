#pragma once
// IMU samples as CAN frames: pure encoders (and decoders for the navemu layouts), no I/O.
// configs/can/navemu.dbc describes every frame built here; tests/protocols/test_can_frames.cpp
// checks the DBC against these encoders signal by signal.
//
// Input: one ImuSample in SI units in navemu's FRD body frame (x forward, y right, z down),
// w_body_radps = angular rate, f_body_mps2 = specific force (at rest, level: f_z = -g).
//
// ---------------------------------------------------------------------------------------------
// 1. SAE J1939-71 / ISO 11783-7 broadcasts (PDU2, 8 bytes, 29-bit identifier)
// ---------------------------------------------------------------------------------------------
// Identifier (SAE J1939-21): bits 28..26 priority, 25 EDP (0), 24 DP (0), 23..16 PF,
// 15..8 PS, 7..0 source address; PGN = EDP|DP|PF|PS, so id = prio<<26 | PGN<<8 | SA for PDU2.
// Default priority 3: used by the Honeywell TARS-IMU manual examples (0x0CF02AE2) and the
// J1939 default priority of the sibling slope-sensor PGN 61481 SSI2 (Axiomatic UMAX0608xx manual).
//
// ARI, Angular Rate Information, PGN 61482 (0xF02A):
//   byte  bits  field                         scaling
//   1-2   16    pitch rate, extended range    1/128 deg/s per bit, offset -250 deg/s
//   3-4   16    roll rate, extended range     1/128 deg/s per bit, offset -250 deg/s
//   5-6   16    yaw rate, extended range      1/128 deg/s per bit, offset -250 deg/s
//   7.1   2     pitch rate figure of merit    00 functional, 01 degraded, 10 error, 11 n/a
//   7.3   2     roll rate figure of merit
//   7.5   2     yaw rate figure of merit
//   7.7   2     not defined / not supported: sent as 11b
//   8     8     angular rate measurement latency, 0.5 ms per bit, 0..125 ms
// ACCS, Acceleration Sensor, PGN 61485 (0xF02D):
//   1-2   16    lateral acceleration, ext.    0.01 m/s^2 per bit, offset -320 m/s^2
//   3-4   16    longitudinal acceleration     0.01 m/s^2 per bit, offset -320 m/s^2
//   5-6   16    vertical acceleration         0.01 m/s^2 per bit, offset -320 m/s^2
//   7.1/7.3/7.5 2 each: lateral/longitudinal/vertical figure of merit (as ARI)
//   7.7   2     support variable transmission repetition rate: sent as 11b (not available)
//   8     8     measurement latency, 0.5 ms per bit (as ARI; see below)
// Sources checked: Aceinna OpenIMU "CAN J1939 Data Messages" (PF/PS, scaling), Honeywell
// TARS-IMU user manual sect. 7.4/7.5 (byte order, worked examples 0x7D00 = 0, status bits),
// LORD MV5-AR manual sect. 4.2.3 (ACCS FoM bit positions), Forkworks ARI/ACCS headers (FoM
// names, latency 0.5 ms/bit for ARI). Multi-byte values are little-endian (J1939-71 5.1.2).
// J1939-71 ranges for 2-byte parameters: 0x0000..0xFAFF valid, 0xFE00..0xFEFF error indicator,
// 0xFF00..0xFFFF not available; 1-byte: 0..250 valid, 0xFE error, 0xFF not available.
//
// Axis mapping (SAE J670 vehicle axes x forward, y right, z down, which J1939 slope-sensor
// PGNs use per the Axiomatic manual; identical to navemu's FRD):
//   roll rate  = +w_x (right wing down positive)
//   pitch rate = +w_y (nose up positive)
//   yaw rate   = +w_z (turning right positive)
//   longitudinal = +f_x (forward positive)
//   lateral      = +f_y (right positive)
//   vertical     = -f_z (up positive, so a unit at rest reports +1 g, as in the TARS and
//                  MV5-AR ACCS examples, both of which use a z-up vertical axis)
// Encoding rules: a finite value outside the data range is clamped to 0x0000/0xFAFF and its
// figure of merit set to degraded; a non-finite value is sent as 0xFE00 (error indicator)
// with figure of merit error; truth_lost or the sample's saturation flags mark the affected
// axes degraded. Latency outside 0..125 ms is clamped; a non-finite latency is sent as 0xFF.
//
// ---------------------------------------------------------------------------------------------
// 2. navemu high-resolution layout (little-endian, identifiers relative to HighResConfig::base_id)
// ---------------------------------------------------------------------------------------------
// Scales: angular rate int32, 1e-7 rad/s per bit (range +-214.7 rad/s = +-12300 deg/s,
// resolution 0.02 deg/h); specific force int32, 1e-6 m/s^2 per bit (range +-2147 m/s^2
// = +-219 g, resolution 0.1 micro-g). Out-of-range values clamp and set the saturated flag;
// non-finite values are sent as INT32_MIN and set the saturated flag.
// flags: bit 0 truth lost, bit 1 gyro saturated, bit 2 accel saturated, bits 3..7 zero.
//
// Classic CAN, five 8-byte frames sent in this order; the STATUS frame closes the sample:
//   id        name          bytes 0-3            bytes 4-7
//   base+0    HR_TIME       gps_time_ns, uint64 (ns since the GPS epoch 1980-01-06)
//   base+1    HR_GYRO_XY    w_x int32            w_y int32
//   base+2    HR_GYRO_Z_AX  w_z int32            f_x int32
//   base+3    HR_ACC_YZ     f_y int32            f_z int32
//   base+4    HR_STATUS     0-1 sequence u16, 2 flags u8, 3 reserved 0,
//                           4-5 CRC-16, 6-7 reserved 0
// CAN FD, one 64-byte frame, id base+0x10 (HR_FD):
//   off  size  field
//     0     8  gps_time_ns uint64
//     8    12  w_x, w_y, w_z int32
//    20    12  f_x, f_y, f_z int32
//    32     2  sequence u16
//    34     1  flags
//    35     1  reserved 0
//    36     2  CRC-16
//    38    26  reserved 0
// CRC: CRC-16/CCITT-FALSE (poly 0x1021, init 0xFFFF, no reflection, xorout 0; check value
// 0x29B1 over "123456789", per the reveng CRC catalogue) over the 36 bytes
// time | gyro xyz | accel xyz | sequence | flags | reserved, i.e. FD bytes 0..35, which are
// also the classic frames' bytes TIME 0-7, GYRO_XY, GYRO_Z_AX, ACC_YZ, STATUS 0-3 in order.
// Both variants therefore carry the same CRC for the same sample.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

namespace navemu::can {

struct CanFrame {
  std::uint32_t id = 0;  // 11-bit or 29-bit identifier, no flag bits
  bool extended = false;
  bool fd = false;
  std::uint8_t len = 0;  // bytes used in data (classic 0..8; FD 0..8,12,16,20,24,32,48,64)
  std::array<std::uint8_t, 64> data{};
};

struct ImuSample {
  std::int64_t gps_time_ns = 0;   // time of validity, ns since the GPS epoch
  std::uint16_t sequence = 0;     // increments by one per output period, wraps
  std::array<double, 3> w_body_radps{};  // FRD body angular rate
  std::array<double, 3> f_body_mps2{};   // FRD body specific force
  double latency_s = 0.0;         // measurement to transmission (J1939 latency byte)
  bool truth_lost = false;        // truth input stale: values extrapolated/held
  bool gyro_saturated = false;    // the IMU model clipped a rate axis
  bool accel_saturated = false;   // the IMU model clipped an accelerometer axis
};

// ---- SAE J1939 -----------------------------------------------------------------------------

namespace j1939 {

inline constexpr std::uint32_t kPgnAri = 61482;   // 0xF02A
inline constexpr std::uint32_t kPgnAccs = 61485;  // 0xF02D
inline constexpr std::uint8_t kDefaultPriority = 3;
inline constexpr std::uint8_t kDefaultSourceAddress = 0x80;

inline constexpr std::uint16_t kMaxValid16 = 0xFAFF;
inline constexpr std::uint16_t kError16 = 0xFE00;
inline constexpr std::uint16_t kNotAvailable16 = 0xFFFF;
inline constexpr std::uint8_t kMaxValid8 = 250;
inline constexpr std::uint8_t kNotAvailable8 = 0xFF;

inline constexpr double kRateResolutionDegps = 1.0 / 128.0;
inline constexpr double kRateOffsetDegps = -250.0;
inline constexpr double kAccelResolutionMps2 = 0.01;
inline constexpr double kAccelOffsetMps2 = -320.0;
inline constexpr double kLatencyResolutionMs = 0.5;

enum class FigureOfMerit : std::uint8_t {
  kFullyFunctional = 0,
  kDegraded = 1,
  kError = 2,
  kNotAvailable = 3,
};

struct Config {
  std::uint8_t priority = kDefaultPriority;  // 0..7, masked
  std::uint8_t source_address = kDefaultSourceAddress;
};

// 29-bit identifier for a PDU2 (PF >= 240) broadcast PGN: prio<<26 | PGN<<8 | SA.
std::uint32_t make_id(std::uint8_t priority, std::uint32_t pgn, std::uint8_t source_address);

// A 2-byte J1939 parameter: raw value and whether it was in range (see the rules above).
struct Raw16 {
  std::uint16_t raw = kNotAvailable16;
  FigureOfMerit fom = FigureOfMerit::kNotAvailable;
};
Raw16 encode_u16(double value, double resolution, double offset);
std::uint8_t encode_latency(double latency_s);

CanFrame encode_ari(const ImuSample& sample, const Config& config = {});
CanFrame encode_accs(const ImuSample& sample, const Config& config = {});

}  // namespace j1939

// ---- navemu high-resolution layout ---------------------------------------------------------

namespace highres {

inline constexpr double kRateLsbRadps = 1e-7;
inline constexpr double kAccelLsbMps2 = 1e-6;
inline constexpr std::uint8_t kFlagTruthLost = 0x01;
inline constexpr std::uint8_t kFlagGyroSaturated = 0x02;
inline constexpr std::uint8_t kFlagAccelSaturated = 0x04;

inline constexpr std::uint32_t kOffsetTime = 0;
inline constexpr std::uint32_t kOffsetGyroXy = 1;
inline constexpr std::uint32_t kOffsetGyroZAccX = 2;
inline constexpr std::uint32_t kOffsetAccYz = 3;
inline constexpr std::uint32_t kOffsetStatus = 4;
inline constexpr std::uint32_t kOffsetFd = 0x10;
inline constexpr std::size_t kClassicFrameCount = 5;
inline constexpr std::size_t kCrcInputSize = 36;

struct Config {
  std::uint32_t base_id = 0x500;
  bool extended = false;  // 29-bit identifiers
};

// CRC-16/CCITT-FALSE: poly 0x1021, init 0xFFFF, refin/refout false, xorout 0.
std::uint16_t crc16_ccitt_false(std::span<const std::uint8_t> bytes);

std::array<CanFrame, kClassicFrameCount> encode_classic(const ImuSample& sample,
                                                        const Config& config = {});
CanFrame encode_fd(const ImuSample& sample, const Config& config = {});

// Decoded wire values (raw integers and their SI equivalents).
struct Decoded {
  std::int64_t gps_time_ns = 0;
  std::uint16_t sequence = 0;
  std::uint8_t flags = 0;
  std::array<std::int32_t, 3> w_raw{};
  std::array<std::int32_t, 3> f_raw{};
  std::array<double, 3> w_body_radps{};
  std::array<double, 3> f_body_mps2{};
};

// nullopt on wrong ids/lengths/order or CRC mismatch. `frames` are the five classic frames in
// transmission order.
std::optional<Decoded> decode_classic(std::span<const CanFrame> frames, const Config& config = {});
std::optional<Decoded> decode_fd(const CanFrame& frame, const Config& config = {});

}  // namespace highres

}  // namespace navemu::can
