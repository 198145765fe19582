// Tests for protocols/can_frames: J1939 ARI/ACCS byte vectors, the navemu high-resolution
// layout, and configs/can/navemu.dbc checked signal by signal against the encoders.
#include "protocols/can_frames.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <map>
#include <regex>
#include <string>
#include <vector>

namespace {

using navemu::can::CanFrame;
using navemu::can::ImuSample;
namespace j1939 = navemu::can::j1939;
namespace highres = navemu::can::highres;

constexpr double kDegToRad = 3.14159265358979323846 / 180.0;

std::vector<std::uint8_t> bytes_of(const CanFrame& f) {
  return {f.data.begin(), f.data.begin() + f.len};
}

// ---- J1939 ---------------------------------------------------------------------------------

TEST(J1939Can, IdentifierComposition) {
  EXPECT_EQ(j1939::make_id(6, 0xF02A, 0x80), 0x18F02A80u);
  EXPECT_EQ(j1939::make_id(3, 0xF02D, 0xE2), 0x0CF02DE2u);  // TARS-IMU manual example id
  EXPECT_EQ(j1939::make_id(7, 0xF02A, 0x00), 0x1CF02A00u);
  const CanFrame ari = j1939::encode_ari(ImuSample{});
  EXPECT_EQ(ari.id, 0x0CF02A80u);
  EXPECT_TRUE(ari.extended);
  EXPECT_FALSE(ari.fd);
  EXPECT_EQ(ari.len, 8);
  const CanFrame accs = j1939::encode_accs(ImuSample{}, {6, 0x80});
  EXPECT_EQ(accs.id, 0x18F02D80u);
}

TEST(J1939Can, AriKnownBytes) {
  ImuSample s;
  s.w_body_radps = {2.0 * kDegToRad, 1.0 * kDegToRad, -1.0 * kDegToRad};  // roll, pitch, yaw
  s.latency_s = 0.005;
  const CanFrame f = j1939::encode_ari(s);
  // pitch +1 deg/s -> 32128 = 0x7D80; roll +2 -> 32256 = 0x7E00; yaw -1 -> 31872 = 0x7C80;
  // FoMs 00, bits 7-8 11b -> 0xC0; 5 ms / 0.5 ms -> 10.
  const std::vector<std::uint8_t> expected{0x80, 0x7D, 0x00, 0x7E, 0x80, 0x7C, 0xC0, 0x0A};
  EXPECT_EQ(bytes_of(f), expected);
}

TEST(J1939Can, AriZeroMatchesTarsExample) {
  ImuSample s;
  s.latency_s = 0.0025;  // -> 5
  const std::vector<std::uint8_t> expected{0x00, 0x7D, 0x00, 0x7D, 0x00, 0x7D, 0xC0, 0x05};
  EXPECT_EQ(bytes_of(j1939::encode_ari(s)), expected);
}

TEST(J1939Can, AccsKnownBytes) {
  ImuSample s;
  s.f_body_mps2 = {-2.0, 1.5, -9.80665};  // forward, right, down (at rest: f_z = -g)
  s.latency_s = 0.0025;
  const CanFrame f = j1939::encode_accs(s);
  // lateral +1.5 -> 32150 = 0x7D96; longitudinal -2 -> 31800 = 0x7C38;
  // vertical +9.80665 (up) -> 32981 = 0x80D5 (as the TARS-IMU manual's +1 g example).
  const std::vector<std::uint8_t> expected{0x96, 0x7D, 0x38, 0x7C, 0xD5, 0x80, 0xC0, 0x05};
  EXPECT_EQ(bytes_of(f), expected);
  EXPECT_EQ(f.id, 0x0CF02D80u);
}

TEST(J1939Can, SaturationErrorAndFlags) {
  ImuSample s;
  s.w_body_radps = {0.0, 300.0 * kDegToRad, std::numeric_limits<double>::quiet_NaN()};
  s.latency_s = 0.2;
  CanFrame f = j1939::encode_ari(s);
  // pitch clamps to 0xFAFF (degraded 01), roll fine (00), yaw error indicator 0xFE00 (10).
  std::vector<std::uint8_t> expected{0xFF, 0xFA, 0x00, 0x7D, 0x00, 0xFE,
                                     0xC0 | 0x01 | (0x02 << 4), 250};
  EXPECT_EQ(bytes_of(f), expected);

  s.w_body_radps = {-300.0 * kDegToRad, 0.0, 0.0};
  s.latency_s = std::numeric_limits<double>::quiet_NaN();
  f = j1939::encode_ari(s);
  expected = {0x00, 0x7D, 0x00, 0x00, 0x00, 0x7D, 0xC0 | (0x01 << 2), 0xFF};
  EXPECT_EQ(bytes_of(f), expected);

  // Just inside the data range: 251.99 deg/s -> 64255 = 0xFAFF, functional.
  EXPECT_EQ(j1939::encode_u16(64255.0 / 128.0 - 250.0, 1.0 / 128.0, -250.0).raw, 0xFAFF);
  EXPECT_EQ(j1939::encode_u16(64255.0 / 128.0 - 250.0, 1.0 / 128.0, -250.0).fom,
            j1939::FigureOfMerit::kFullyFunctional);

  // Model saturation / truth loss mark the affected message degraded.
  ImuSample a;
  a.accel_saturated = true;
  EXPECT_EQ(j1939::encode_accs(a).data[6], 0xC0 | 0x15);
  EXPECT_EQ(j1939::encode_ari(a).data[6], 0xC0);
  a.accel_saturated = false;
  a.truth_lost = true;
  EXPECT_EQ(j1939::encode_ari(a).data[6], 0xC0 | 0x15);
  a.f_body_mps2 = {0.0, 400.0, 0.0};
  const CanFrame accs = j1939::encode_accs(a);
  EXPECT_EQ(accs.data[0], 0xFF);
  EXPECT_EQ(accs.data[1], 0xFA);
}

TEST(J1939Can, LatencyByte) {
  EXPECT_EQ(j1939::encode_latency(0.0), 0);
  EXPECT_EQ(j1939::encode_latency(0.0105), 21);
  EXPECT_EQ(j1939::encode_latency(0.125), 250);
  EXPECT_EQ(j1939::encode_latency(1.0), 250);
  EXPECT_EQ(j1939::encode_latency(-0.001), 0);
  EXPECT_EQ(j1939::encode_latency(std::numeric_limits<double>::infinity()), 0xFF);
}

// ---- navemu high-resolution layout -------------------------------------------------------

TEST(CanHighRes, CrcCheckValue) {
  const std::string check = "123456789";
  const std::vector<std::uint8_t> v(check.begin(), check.end());
  EXPECT_EQ(highres::crc16_ccitt_false(v), 0x29B1);  // reveng catalogue check value
  EXPECT_EQ(highres::crc16_ccitt_false({}), 0xFFFF);
}

ImuSample simple_sample() {
  ImuSample s;
  s.gps_time_ns = 0x0102030405060708;
  s.sequence = 0x1234;
  s.w_body_radps = {1.0, 0.0, -1.0};
  s.f_body_mps2 = {0.0, 0.0, -9.80665};
  s.truth_lost = true;
  return s;
}

TEST(CanHighRes, FdKnownBytes) {
  const CanFrame f = highres::encode_fd(simple_sample());
  EXPECT_EQ(f.id, 0x510u);
  EXPECT_FALSE(f.extended);
  EXPECT_TRUE(f.fd);
  EXPECT_EQ(f.len, 64);
  std::vector<std::uint8_t> expected{
      0x08, 0x07, 0x06, 0x05, 0x04, 0x03, 0x02, 0x01,  // time
      0x80, 0x96, 0x98, 0x00,                          // w_x 1 rad/s = 10^7
      0x00, 0x00, 0x00, 0x00,                          // w_y
      0x80, 0x69, 0x67, 0xFF,                          // w_z -10^7
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // f_x, f_y
      0xC6, 0x5C, 0x6A, 0xFF,                          // f_z -9806650
      0x34, 0x12, 0x01, 0x00,                          // sequence, flags, reserved
      0xFF, 0x68};  // CRC-16/CCITT-FALSE of bytes 0..35, computed independently (Python)
  expected.resize(64, 0x00);
  EXPECT_EQ(bytes_of(f), expected);
}

TEST(CanHighRes, ClassicFramesAndCrcMatchFd) {
  const auto frames = highres::encode_classic(simple_sample());
  const CanFrame fd = highres::encode_fd(simple_sample());
  for (std::size_t k = 0; k < frames.size(); ++k) {
    EXPECT_EQ(frames[k].id, 0x500u + k);
    EXPECT_EQ(frames[k].len, 8);
    EXPECT_FALSE(frames[k].fd);
    EXPECT_FALSE(frames[k].extended);
  }
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_TRUE(std::equal(frames[k].data.begin(), frames[k].data.begin() + 8,
                           fd.data.begin() + static_cast<std::ptrdiff_t>(8 * k)));
  }
  const std::vector<std::uint8_t> status{0x34, 0x12, 0x01, 0x00, 0xFF, 0x68, 0x00, 0x00};
  EXPECT_EQ(bytes_of(frames[4]), status);
}

TEST(CanHighRes, RoundTrip) {
  ImuSample s;
  s.gps_time_ns = 1'400'000'000'123'456'789;
  s.sequence = 65535;
  s.w_body_radps = {0.12345678, -34.9, 2000.0 * kDegToRad};
  s.f_body_mps2 = {1.2345678, -156.9, -9.80665};
  s.gyro_saturated = true;
  for (const highres::Config config : {highres::Config{}, highres::Config{0x18FF0000, true}}) {
    const auto frames = highres::encode_classic(s, config);
    const auto classic = highres::decode_classic(frames, config);
    const auto fd = highres::decode_fd(highres::encode_fd(s, config), config);
    ASSERT_TRUE(classic.has_value());
    ASSERT_TRUE(fd.has_value());
    for (const auto& d : {*classic, *fd}) {
      EXPECT_EQ(d.gps_time_ns, s.gps_time_ns);
      EXPECT_EQ(d.sequence, s.sequence);
      EXPECT_EQ(d.flags, highres::kFlagGyroSaturated);
      for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_NEAR(d.w_body_radps[i], s.w_body_radps[i], 0.5 * highres::kRateLsbRadps * 1.001);
        EXPECT_NEAR(d.f_body_mps2[i], s.f_body_mps2[i], 0.5 * highres::kAccelLsbMps2 * 1.001);
      }
    }
    // Corruption or a wrong frame set is refused.
    auto bad = frames;
    bad[2].data[3] ^= 0x10;
    EXPECT_FALSE(highres::decode_classic(bad, config).has_value());
    std::swap(bad[1], bad[2]);
    EXPECT_FALSE(highres::decode_classic(bad, config).has_value());
    CanFrame bad_fd = highres::encode_fd(s, config);
    bad_fd.data[0] ^= 1;
    EXPECT_FALSE(highres::decode_fd(bad_fd, config).has_value());
  }
  EXPECT_EQ(highres::encode_classic(s, {0x18FF0000, true})[4].id, 0x18FF0004u);
}

TEST(CanHighRes, SaturationSetsFlags) {
  ImuSample s;
  s.w_body_radps = {1000.0, 0.0, 0.0};  // beyond +-214.7 rad/s
  s.f_body_mps2 = {0.0, std::numeric_limits<double>::quiet_NaN(), 0.0};
  const auto d = highres::decode_fd(highres::encode_fd(s));
  ASSERT_TRUE(d.has_value());
  EXPECT_EQ(d->w_raw[0], std::numeric_limits<std::int32_t>::max());
  EXPECT_EQ(d->f_raw[1], std::numeric_limits<std::int32_t>::min());
  EXPECT_EQ(d->flags, highres::kFlagGyroSaturated | highres::kFlagAccelSaturated);
  s.w_body_radps = {-1000.0, 0.0, 0.0};
  s.f_body_mps2 = {};
  const auto n = highres::decode_fd(highres::encode_fd(s));
  ASSERT_TRUE(n.has_value());
  EXPECT_EQ(n->w_raw[0], std::numeric_limits<std::int32_t>::min());
  EXPECT_EQ(n->flags, highres::kFlagGyroSaturated);
}

// ---- configs/can/navemu.dbc against the encoders ----------------------------------------

struct DbcSignal {
  std::string name;
  unsigned start = 0;
  unsigned length = 0;
  bool little_endian = true;
  bool is_signed = false;
  double factor = 1.0;
  double offset = 0.0;
  double min = 0.0;
  double max = 0.0;
  std::string unit;
};

struct DbcMessage {
  std::uint32_t id = 0;
  bool extended = false;
  std::string name;
  unsigned length = 0;
  std::vector<DbcSignal> signals;
};

// Minimal DBC reader: BO_ and SG_ lines only (no multiplexing).
std::vector<DbcMessage> parse_dbc(const std::string& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << "cannot open " << path;
  const std::regex bo(R"(^BO_\s+(\d+)\s+(\w+)\s*:\s*(\d+)\s+\w+\s*$)");
  const std::regex sg(
      R"(^\s+SG_\s+(\w+)\s*:\s*(\d+)\|(\d+)@([01])([+-])\s*\(([^,]+),([^)]+)\)\s*)"
      R"(\[([^|]+)\|([^\]]+)\]\s*"([^"]*)\"\s+.*$)");
  std::vector<DbcMessage> messages;
  std::string line;
  std::smatch m;
  while (std::getline(in, line)) {
    if (std::regex_match(line, m, bo)) {
      DbcMessage msg;
      const std::uint64_t raw_id = std::stoull(m[1].str());
      msg.extended = (raw_id & 0x80000000u) != 0;
      msg.id = static_cast<std::uint32_t>(raw_id & 0x1FFFFFFFu);
      msg.name = m[2].str();
      msg.length = static_cast<unsigned>(std::stoul(m[3].str()));
      messages.push_back(msg);
    } else if (std::regex_match(line, m, sg)) {
      EXPECT_FALSE(messages.empty()) << line;
      if (messages.empty()) continue;
      DbcSignal s;
      s.name = m[1].str();
      s.start = static_cast<unsigned>(std::stoul(m[2].str()));
      s.length = static_cast<unsigned>(std::stoul(m[3].str()));
      s.little_endian = m[4].str() == "1";
      s.is_signed = m[5].str() == "-";
      s.factor = std::stod(m[6].str());
      s.offset = std::stod(m[7].str());
      s.min = std::stod(m[8].str());
      s.max = std::stod(m[9].str());
      s.unit = m[10].str();
      messages.back().signals.push_back(s);
    } else {
      EXPECT_EQ(line.rfind(" SG_", 0), std::string::npos) << "unparsed: " << line;
    }
  }
  return messages;
}

// Intel (little-endian) extraction: bit i of the payload is data[i/8] bit (i%8).
std::uint64_t extract_raw(const CanFrame& f, const DbcSignal& s) {
  std::uint64_t raw = 0;
  for (unsigned i = 0; i < s.length; ++i) {
    const unsigned bit = s.start + i;
    if (((static_cast<unsigned>(f.data[bit / 8]) >> (bit % 8)) & 1u) != 0) raw |= std::uint64_t{1} << i;
  }
  return raw;
}

std::int64_t sign_extend(std::uint64_t raw, unsigned length) {
  if (length < 64 && ((raw >> (length - 1)) & 1u) != 0) raw |= ~std::uint64_t{0} << length;
  return static_cast<std::int64_t>(raw);
}

// The physical value every DBC signal should carry for sample s, written from the layout
// tables (not from the encoder): "Message.Signal" -> value.
struct Expected {
  double value = 0.0;
  bool exact_integer = false;  // compare raw integers (64-bit time)
  std::uint64_t integer = 0;
};

double clamp_j1939(double v, double res, double off) {
  return std::clamp(v, off, off + 64255.0 * res);
}

// Figures of merit per axis: ari {pitch, roll, yaw}, accs {lateral, longitudinal, vertical}.
std::map<std::string, Expected> expectations(const ImuSample& s, std::array<unsigned, 3> ari,
                                             std::array<unsigned, 3> accs) {
  constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;
  std::map<std::string, Expected> e;
  const double r = 1.0 / 128.0;
  e["ARI.PitchRate"] = {clamp_j1939(s.w_body_radps[1] * kRadToDeg, r, -250.0)};
  e["ARI.RollRate"] = {clamp_j1939(s.w_body_radps[0] * kRadToDeg, r, -250.0)};
  e["ARI.YawRate"] = {clamp_j1939(s.w_body_radps[2] * kRadToDeg, r, -250.0)};
  e["ARI.PitchRateFoM"] = {double(ari[0])};
  e["ARI.RollRateFoM"] = {double(ari[1])};
  e["ARI.YawRateFoM"] = {double(ari[2])};
  e["ARI.Latency"] = e["ACCS.Latency"] = {s.latency_s * 1000.0};
  e["ACCS.LateralAccel"] = {clamp_j1939(s.f_body_mps2[1], 0.01, -320.0)};
  e["ACCS.LongitudinalAccel"] = {clamp_j1939(s.f_body_mps2[0], 0.01, -320.0)};
  e["ACCS.VerticalAccel"] = {clamp_j1939(-s.f_body_mps2[2], 0.01, -320.0)};
  e["ACCS.LateralAccelFoM"] = {double(accs[0])};
  e["ACCS.LongitudinalAccelFoM"] = {double(accs[1])};
  e["ACCS.VerticalAccelFoM"] = {double(accs[2])};
  const std::uint16_t crc = highres::crc16_ccitt_false(
      std::span<const std::uint8_t>(highres::encode_fd(s).data.data(), highres::kCrcInputSize));
  for (const std::string m : {"HR_", "HR_FD."}) {
    const bool fd = m == "HR_FD.";
    const auto key = [&](const char* frame, const char* sig) {
      return fd ? m + sig : std::string("HR_") + frame + "." + sig;
    };
    e[key("TIME", "GpsTimeNs")] = {0.0, true, static_cast<std::uint64_t>(s.gps_time_ns)};
    e[key("GYRO_XY", "GyroX")] = {s.w_body_radps[0]};
    e[key("GYRO_XY", "GyroY")] = {s.w_body_radps[1]};
    e[key("GYRO_Z_AX", "GyroZ")] = {s.w_body_radps[2]};
    e[key("GYRO_Z_AX", "AccelX")] = {s.f_body_mps2[0]};
    e[key("ACC_YZ", "AccelY")] = {s.f_body_mps2[1]};
    e[key("ACC_YZ", "AccelZ")] = {s.f_body_mps2[2]};
    e[key("STATUS", "Sequence")] = {double(s.sequence)};
    e[key("STATUS", "FlagTruthLost")] = {s.truth_lost ? 1.0 : 0.0};
    e[key("STATUS", "FlagGyroSaturated")] = {s.gyro_saturated ? 1.0 : 0.0};
    e[key("STATUS", "FlagAccelSaturated")] = {s.accel_saturated ? 1.0 : 0.0};
    e[key("STATUS", "Crc")] = {double(crc)};
  }
  return e;
}

void check_dbc_against(const ImuSample& s, const std::map<std::string, Expected>& expected) {
  const auto messages = parse_dbc(std::string(NAVEMU_SOURCE_DIR) + "/configs/can/navemu.dbc");
  std::vector<CanFrame> frames{j1939::encode_ari(s), j1939::encode_accs(s)};
  for (const CanFrame& f : highres::encode_classic(s)) frames.push_back(f);
  frames.push_back(highres::encode_fd(s));
  ASSERT_EQ(messages.size(), frames.size()) << "one BO_ per frame navemu emits";
  std::size_t signals_checked = 0;
  for (const CanFrame& f : frames) {
    const auto it = std::find_if(messages.begin(), messages.end(), [&](const DbcMessage& m) {
      return m.id == f.id && m.extended == f.extended;
    });
    ASSERT_NE(it, messages.end()) << "no BO_ for id 0x" << std::hex << f.id;
    EXPECT_EQ(it->length, f.len) << it->name;
    for (const DbcSignal& sig : it->signals) {
      const std::string key = it->name + "." + sig.name;
      SCOPED_TRACE(key);
      EXPECT_TRUE(sig.little_endian);
      ASSERT_LE(sig.start + sig.length, 8u * f.len);
      EXPECT_LE(sig.min, sig.max);
      const auto e = expected.find(key);
      ASSERT_NE(e, expected.end()) << "signal without an expectation";
      const std::uint64_t raw = extract_raw(f, sig);
      if (e->second.exact_integer) {
        EXPECT_EQ(sig.factor, 1.0);
        EXPECT_EQ(sig.offset, 0.0);
        EXPECT_EQ(raw, e->second.integer);
      } else {
        const double raw_d = sig.is_signed ? static_cast<double>(sign_extend(raw, sig.length))
                                           : static_cast<double>(raw);
        const double physical = raw_d * sig.factor + sig.offset;
        // The encoders round to nearest: within half an LSB (tighter than one LSB, so that
        // 0/1 flags and figures of merit are compared exactly).
        EXPECT_NEAR(physical, e->second.value, sig.factor * 0.5000001);
        EXPECT_GE(physical, sig.min - sig.factor);
        EXPECT_LE(physical, sig.max + sig.factor);
      }
      ++signals_checked;
    }
  }
  EXPECT_EQ(signals_checked, expected.size()) << "every expectation matched a DBC signal";
}

TEST(DbcCan, EverySignalMatchesEncoderNominal) {
  ImuSample s;
  s.gps_time_ns = 1'400'000'000'123'456'789;
  s.sequence = 4660;
  s.w_body_radps = {0.1234567, -0.7654321, 1.5};
  s.f_body_mps2 = {1.25, -0.5, -9.80665};
  s.latency_s = 0.004;
  check_dbc_against(s, expectations(s, {0, 0, 0}, {0, 0, 0}));
}

TEST(DbcCan, EverySignalMatchesEncoderFlagsAndClamping) {
  ImuSample s;
  s.gps_time_ns = 1'234'567'890'000'000'001;
  s.sequence = 65535;
  s.w_body_radps = {-3.0, 2.5, -0.001};
  s.f_body_mps2 = {-30.0, 400.0, 12.0};  // lateral clamps to 322.55 (degraded)
  s.latency_s = 0.0105;
  s.gyro_saturated = true;
  s.truth_lost = true;
  s.accel_saturated = false;
  check_dbc_against(s, expectations(s, {1, 1, 1}, {1, 1, 1}));  // truth lost: all degraded
  s.truth_lost = false;
  check_dbc_against(s, expectations(s, {1, 1, 1}, {1, 0, 0}));
  // One axis out of range at a time gives distinct figure-of-merit patterns.
  s.gyro_saturated = false;
  s.w_body_radps = {0.1, 0.2, 5.0};  // yaw 286 deg/s clamps
  s.f_body_mps2 = {0.0, 0.0, 400.0};  // vertical -400 clamps to -320
  check_dbc_against(s, expectations(s, {0, 0, 1}, {0, 0, 1}));
  s.w_body_radps = {-5.0, 0.2, 0.1};  // roll clamps
  s.f_body_mps2 = {-400.0, 0.0, 0.0};  // longitudinal clamps
  check_dbc_against(s, expectations(s, {0, 1, 0}, {0, 1, 0}));
}

}  // namespace
