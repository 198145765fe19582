// The truth datagram codec: CRC, the binary layout pinned byte by byte independently of the
// encoder, round trips of every flag combination, and the refusals of bad input.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "protocols/truth_datagram.hpp"

namespace navemu::truth_datagram {
namespace {

std::span<const std::uint8_t> bytes_of(std::string_view s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

// Little-endian readers written out here so that the layout checks do not use the codec's own.
std::uint64_t le_u64(std::span<const std::uint8_t> b, std::size_t off) {
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < 8; ++i) v |= std::uint64_t{b[off + i]} << (8 * i);
  return v;
}
std::uint32_t le_u32(std::span<const std::uint8_t> b, std::size_t off) {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < 4; ++i) v |= static_cast<std::uint32_t>(b[off + i]) << (8 * i);
  return v;
}
double le_f64(std::span<const std::uint8_t> b, std::size_t off) {
  return std::bit_cast<double>(le_u64(b, off));
}

// A message with every field distinct (GPS time, geodetic, NED, quaternion, rates and
// temperature present: flags 0x30).
Message sample() {
  Message m;
  m.sequence = 17;
  m.time_ns = 1'400'000'000'123'456'789;
  m.position = {47.3977, 8.5456, 488.25};
  m.velocity_mps = {1.5, -0.25, 0.125};
  m.attitude = {0.7071067811865476, 0.0, 0.0, 0.7071067811865476};
  m.has_rates = true;
  m.f_body_mps2 = {0.1, -0.2, -9.80665};
  m.w_body_radps = {0.001, -0.002, 0.003};
  m.has_temperature = true;
  m.temperature_c = 21.5;
  return m;
}

void expect_same(const Message& a, const Message& b) {
  EXPECT_EQ(a.sequence, b.sequence);
  EXPECT_EQ(a.time_base, b.time_base);
  EXPECT_EQ(a.time_ns, b.time_ns);
  EXPECT_EQ(a.position_frame, b.position_frame);
  EXPECT_EQ(a.position, b.position);
  EXPECT_EQ(a.velocity_frame, b.velocity_frame);
  EXPECT_EQ(a.velocity_mps, b.velocity_mps);
  EXPECT_EQ(a.attitude_form, b.attitude_form);
  EXPECT_EQ(a.attitude, b.attitude);
  EXPECT_EQ(a.has_rates, b.has_rates);
  EXPECT_EQ(a.f_body_mps2, b.f_body_mps2);
  EXPECT_EQ(a.w_body_radps, b.w_body_radps);
  EXPECT_EQ(a.has_temperature, b.has_temperature);
  EXPECT_EQ(a.temperature_c, b.temperature_c);
}

// The message of flag combination `flags` (bits as in the binary header).
Message with_flags(unsigned flags) {
  Message m = sample();
  m.time_base = (flags & 1u) != 0 ? TimeBase::kHostUtc : TimeBase::kGps;
  m.position_frame = (flags & 2u) != 0 ? PositionFrame::kEcef : PositionFrame::kGeodetic;
  if (m.position_frame == PositionFrame::kEcef) m.position = {4'331'297.35, 651'013.9, 4'625'342.1};
  m.velocity_frame = (flags & 4u) != 0 ? VelocityFrame::kEcef : VelocityFrame::kNed;
  m.attitude_form = (flags & 8u) != 0 ? AttitudeForm::kRollPitchYaw : AttitudeForm::kQuaternion;
  if (m.attitude_form == AttitudeForm::kRollPitchYaw) m.attitude = {-1.25, 3.5, 271.0, 0.0};
  m.has_rates = (flags & 16u) != 0;
  if (!m.has_rates) m.f_body_mps2 = m.w_body_radps = {};
  m.has_temperature = (flags & 32u) != 0;
  if (!m.has_temperature) m.temperature_c = 0.0;
  return m;
}

TEST(TruthDatagram, Crc32CheckValue) {
  EXPECT_EQ(crc32(bytes_of("123456789")), 0xCBF43926u);
  EXPECT_EQ(crc32({}), 0u);
}

// zlib.crc32 of the same 156 bytes packed in Python, independently of the encoder:
//   python3 -c "import struct, zlib; print(zlib.crc32(struct.pack('<4sBBHIq3d3d4d3d3dd',
//     b'NVTR', 1, 0, 0x30, 17, 1400000000123456789, 47.3977, 8.5456, 488.25, 1.5, -0.25,
//     0.125, 0.7071067811865476, 0.0, 0.0, 0.7071067811865476, 0.1, -0.2, -9.80665, 0.001,
//     -0.002, 0.003, 21.5)))"
// printed 2358025084.
TEST(TruthDatagram, CrcMatchesPythonZlib) {
  const auto b = encode_binary(sample());
  EXPECT_EQ(crc32(std::span<const std::uint8_t>(b).first(156)), 2358025084u);
  EXPECT_EQ(le_u32(b, 156), 2358025084u);
}

// The layout, built by hand at the documented offsets and decoded.
TEST(TruthDatagram, HandBuiltDatagramDecodes) {
  std::array<std::uint8_t, 160> b{};
  std::memcpy(b.data(), "NVTR", 4);
  b[4] = 1;
  b[6] = 0x2F;  // host UTC, ECEF position and velocity, roll/pitch/yaw, temperature
  b[8] = 0x78;  // sequence 0x12345678
  b[9] = 0x56;
  b[10] = 0x34;
  b[11] = 0x12;
  b[12] = 0xFE;  // time -2 ns, two's complement: FE FF FF FF FF FF FF FF
  for (std::size_t i = 13; i < 20; ++i) b[i] = 0xFF;
  const auto put_f64 = [&](std::size_t off, double v) {
    const auto u = std::bit_cast<std::uint64_t>(v);
    for (std::size_t i = 0; i < 8; ++i) b[off + i] = static_cast<std::uint8_t>(u >> (8 * i));
  };
  put_f64(20, 4'331'297.5);
  put_f64(28, 651'013.25);
  put_f64(36, -4'625'342.125);
  put_f64(44, 1.0);
  put_f64(52, 2.0);
  put_f64(60, 3.0);
  put_f64(68, 10.0);
  put_f64(76, 20.0);
  put_f64(84, 30.0);
  put_f64(148, -40.5);
  const std::uint32_t crc = crc32(std::span<const std::uint8_t>(b).first(156));
  for (std::size_t i = 0; i < 4; ++i) b[156 + i] = static_cast<std::uint8_t>(crc >> (8 * i));

  Message m;
  ASSERT_EQ(decode_binary(b, m), DecodeResult::kOk);
  EXPECT_EQ(m.sequence, 0x12345678u);
  EXPECT_EQ(m.time_base, TimeBase::kHostUtc);
  EXPECT_EQ(m.time_ns, -2);
  EXPECT_EQ(m.position_frame, PositionFrame::kEcef);
  EXPECT_EQ(m.position, (std::array<double, 3>{4'331'297.5, 651'013.25, -4'625'342.125}));
  EXPECT_EQ(m.velocity_frame, VelocityFrame::kEcef);
  EXPECT_EQ(m.velocity_mps, (std::array<double, 3>{1.0, 2.0, 3.0}));
  EXPECT_EQ(m.attitude_form, AttitudeForm::kRollPitchYaw);
  EXPECT_EQ(m.attitude, (std::array<double, 4>{10.0, 20.0, 30.0, 0.0}));
  EXPECT_FALSE(m.has_rates);
  EXPECT_TRUE(m.has_temperature);
  EXPECT_EQ(m.temperature_c, -40.5);
}

// The encoder's bytes at fixed offsets, read with the little-endian readers above.
TEST(TruthDatagram, EncoderLayoutAtFixedOffsets) {
  Message m = sample();
  m.sequence = 0xA1B2C3D4u;
  const auto b = encode_binary(m);
  EXPECT_EQ(std::string(b.begin(), b.begin() + 4), "NVTR");
  EXPECT_EQ(b[4], 1);
  EXPECT_EQ(b[5], 0);
  EXPECT_EQ(b[6], 0x30);
  EXPECT_EQ(b[7], 0x00);
  EXPECT_EQ(b[8], 0xD4);
  EXPECT_EQ(b[11], 0xA1);
  EXPECT_EQ(le_u64(b, 12), 1'400'000'000'123'456'789u);
  // lat 47.3977 = 0x4047B2E7D566CF42 (Python: struct.pack('<d', 47.3977)), least significant
  // byte first.
  EXPECT_EQ(le_u64(b, 20), 0x4047B2E7D566CF42u);
  EXPECT_EQ(b[20], 0x42);
  EXPECT_EQ(b[27], 0x40);
  EXPECT_EQ(le_f64(b, 20), 47.3977);
  EXPECT_EQ(le_f64(b, 36), 488.25);
  EXPECT_EQ(le_f64(b, 44), 1.5);
  EXPECT_EQ(le_f64(b, 68), 0.7071067811865476);
  EXPECT_EQ(le_f64(b, 92), 0.7071067811865476);
  EXPECT_EQ(le_f64(b, 116), -9.80665);
  EXPECT_EQ(le_f64(b, 140), 0.003);
  EXPECT_EQ(le_f64(b, 148), 21.5);
  // Absent blocks are zero.
  const auto c = encode_binary(with_flags(0));
  for (std::size_t i = 100; i < 156; ++i) EXPECT_EQ(c[i], 0) << i;
}

TEST(TruthDatagram, BinaryRoundTripOfEveryFlagCombination) {
  for (unsigned flags = 0; flags < 64; ++flags) {
    const Message m = with_flags(flags);
    const auto b = encode_binary(m);
    EXPECT_EQ(b[6], flags);
    Message back;
    ASSERT_EQ(decode_binary(b, back), DecodeResult::kOk) << flags;
    expect_same(back, m);
    Message via_decode;
    ASSERT_EQ(decode(b, via_decode), DecodeResult::kOk);
    expect_same(via_decode, m);
  }
}

TEST(TruthDatagram, BinaryCarriesExtremeDoublesBitExactly) {
  Message m = sample();
  m.position = {-0.0, std::numeric_limits<double>::denorm_min(),
                std::numeric_limits<double>::max()};
  m.velocity_mps = {std::numeric_limits<double>::infinity(), -1e-300, 1e300};
  m.time_ns = std::numeric_limits<std::int64_t>::min();
  m.sequence = 0xFFFFFFFFu;
  Message back;
  ASSERT_EQ(decode_binary(encode_binary(m), back), DecodeResult::kOk);
  expect_same(back, m);
  EXPECT_TRUE(std::signbit(back.position[0]));
}

TEST(TruthDatagram, EveryCorruptedByteIsCaught) {
  const auto good = encode_binary(sample());
  for (std::size_t i = 0; i < good.size(); ++i) {
    auto b = good;
    b[i] ^= 0x10;
    Message m;
    const DecodeResult r = decode_binary(b, m);
    if (i < 4) {
      EXPECT_EQ(r, DecodeResult::kBadMagic) << i;
    } else if (i == 4) {
      EXPECT_EQ(r, DecodeResult::kBadVersion) << i;
    } else {
      EXPECT_EQ(r, DecodeResult::kBadCrc) << i;
    }
  }
}

TEST(TruthDatagram, WrongMagicVersionLengthAndReservedBits) {
  const auto good = encode_binary(sample());
  Message m = with_flags(0);
  const Message untouched = m;
  auto b = good;
  b[0] = 'X';
  EXPECT_EQ(decode_binary(b, m), DecodeResult::kBadMagic);
  b = good;
  b[4] = 2;  // another version, whatever its CRC
  EXPECT_EQ(decode_binary(b, m), DecodeResult::kBadVersion);
  const std::span<const std::uint8_t> all(good);
  EXPECT_EQ(decode_binary(all.first(159), m), DecodeResult::kBadLength);
  EXPECT_EQ(decode_binary(all.first(4), m), DecodeResult::kBadLength);
  EXPECT_EQ(decode_binary(all.first(0), m), DecodeResult::kBadLength);
  std::vector<std::uint8_t> longer(good.begin(), good.end());
  longer.push_back(0);
  EXPECT_EQ(decode_binary(longer, m), DecodeResult::kBadLength);
  EXPECT_EQ(decode_binary(bytes_of("NVXR"), m), DecodeResult::kBadMagic);
  EXPECT_EQ(decode_binary(bytes_of("N"), m), DecodeResult::kBadLength);
  // Reserved byte and undefined flag bits, with a valid CRC: refused as another version.
  for (const std::size_t off : {std::size_t{5}, std::size_t{6}, std::size_t{7}}) {
    b = good;
    b[off] |= 0x80;
    const std::uint32_t crc = crc32(std::span<const std::uint8_t>(b).first(156));
    for (std::size_t i = 0; i < 4; ++i) b[156 + i] = static_cast<std::uint8_t>(crc >> (8 * i));
    EXPECT_EQ(decode_binary(b, m), DecodeResult::kBadVersion) << off;
  }
  expect_same(m, untouched);  // nothing written on failure
}

// ---- JSON --------------------------------------------------------------------------------------

TEST(TruthDatagram, JsonRoundTripOfEveryFlagCombination) {
  for (unsigned flags = 0; flags < 64; ++flags) {
    const Message m = with_flags(flags);
    const std::string j = encode_json(m);
    EXPECT_EQ(j.find('\n'), std::string::npos);
    Message back;
    ASSERT_EQ(decode_json(j, back), DecodeResult::kOk) << j;
    expect_same(back, m);
    Message via_decode;
    ASSERT_EQ(decode(bytes_of(j), via_decode), DecodeResult::kOk);
    expect_same(via_decode, m);
  }
}

TEST(TruthDatagram, JsonIsReadableAndExact) {
  EXPECT_EQ(encode_json(sample()),
            R"({"seq":17,"t_gps_ns":1400000000123456789,"lat_deg":47.3977,"lon_deg":8.5456,)"
            R"("h_m":488.25,"v_n_mps":1.5,"v_e_mps":-0.25,"v_d_mps":0.125,)"
            R"("qw":0.7071067811865476,"qx":0,"qy":0,"qz":0.7071067811865476,"f_x_mps2":0.1,)"
            R"("f_y_mps2":-0.2,"f_z_mps2":-9.80665,"w_x_radps":0.001,"w_y_radps":-0.002,)"
            R"("w_z_radps":0.003,"temperature_c":21.5})");
  // Shortest representations read back to the same doubles.
  std::mt19937_64 rng(7);
  for (int i = 0; i < 1000; ++i) {
    Message m = with_flags(static_cast<unsigned>(rng() % 64));
    for (double& v : m.position) v = std::bit_cast<double>(rng() >> 2);  // finite, any exponent
    m.time_ns = static_cast<std::int64_t>(rng());
    Message back;
    ASSERT_EQ(decode_json(encode_json(m), back), DecodeResult::kOk) << encode_json(m);
    expect_same(back, m);
  }
}

TEST(TruthDatagram, JsonAcceptsSpacingNewlineAndUnknownKeys) {
  const std::string line =
      "{ \"seq\": 3, \"t_unix_ns\": -5, \"x_m\": 1e3, \"y_m\": -2.5E-1, \"z_m\": 0,\n"
      "  \"vx_mps\": 0, \"vy_mps\": 0, \"vz_mps\": 0, \"roll_deg\": 1, \"pitch_deg\": 2,"
      " \"yaw_deg\": 3, \"source\": \"gazebo\", \"version\": 1 }\n";
  Message m;
  ASSERT_EQ(decode_json(line, m), DecodeResult::kOk);
  EXPECT_EQ(m.sequence, 3u);
  EXPECT_EQ(m.time_base, TimeBase::kHostUtc);
  EXPECT_EQ(m.time_ns, -5);
  EXPECT_EQ(m.position_frame, PositionFrame::kEcef);
  EXPECT_EQ(m.position, (std::array<double, 3>{1000.0, -0.25, 0.0}));
  EXPECT_EQ(m.attitude_form, AttitudeForm::kRollPitchYaw);
  EXPECT_EQ(m.attitude, (std::array<double, 4>{1.0, 2.0, 3.0, 0.0}));
  EXPECT_FALSE(m.has_rates);
  EXPECT_FALSE(m.has_temperature);
}

TEST(TruthDatagram, JsonTimeIsAnExactInt64) {
  Message m;
  const std::string base = R"("lat_deg":1,"lon_deg":2,"h_m":3,"v_n_mps":0,"v_e_mps":0,"v_d_mps":0,)"
                           R"("qw":1,"qx":0,"qy":0,"qz":0})";
  ASSERT_EQ(decode_json(R"({"seq":0,"t_gps_ns":9007199254740993,)" + base, m), DecodeResult::kOk);
  EXPECT_EQ(m.time_ns, 9'007'199'254'740'993);  // 2^53 + 1: not a double
  ASSERT_EQ(decode_json(R"({"seq":4294967295,"t_gps_ns":9223372036854775807,)" + base, m),
            DecodeResult::kOk);
  EXPECT_EQ(m.time_ns, std::numeric_limits<std::int64_t>::max());
  EXPECT_EQ(m.sequence, 4294967295u);
  for (const char* bad : {R"("seq":0,"t_gps_ns":9223372036854775808,)",  // int64 overflow
                          R"("seq":0,"t_gps_ns":1.5e18,)",               // not an integer
                          R"("seq":0,"t_gps_ns":100.0,)",
                          R"("seq":4294967296,"t_gps_ns":1,)",  // uint32 overflow
                          R"("seq":-1,"t_gps_ns":1,)", R"("seq":0,"t_gps_ns":"1",)"}) {
    EXPECT_EQ(decode_json(std::string("{") + bad + base, m), DecodeResult::kBadJson) << bad;
  }
}

TEST(TruthDatagram, JsonMissingOrDoubledGroups) {
  const std::string full = encode_json(with_flags(0x30));
  const auto without = [&](const std::string& key) {
    std::string s = full;
    const auto k = s.find("\"" + key + "\"");
    const auto end = s.find_first_of(",}", k);
    s.erase(k, end - k + (s[end] == ',' ? 1 : 0));
    if (s[s.size() - 2] == ',') s.erase(s.size() - 2, 1);
    return s;
  };
  const auto with = [&](const std::string& extra) {
    return full.substr(0, full.size() - 1) + "," + extra + "}";
  };
  Message m;
  for (const char* key :
       {"seq", "t_gps_ns", "lat_deg", "h_m", "v_d_mps", "qx", "f_y_mps2", "w_z_radps"}) {
    EXPECT_EQ(decode_json(without(key), m), DecodeResult::kMissingField) << key;
  }
  EXPECT_EQ(decode_json(without("temperature_c"), m), DecodeResult::kOk);
  EXPECT_EQ(decode_json(with(R"("t_unix_ns":1)"), m), DecodeResult::kMissingField);
  EXPECT_EQ(decode_json(with(R"("x_m":1,"y_m":2,"z_m":3)"), m), DecodeResult::kMissingField);
  EXPECT_EQ(decode_json(with(R"("vx_mps":1)"), m), DecodeResult::kMissingField);
  EXPECT_EQ(decode_json(with(R"("roll_deg":1,"pitch_deg":2,"yaw_deg":3)"), m),
            DecodeResult::kMissingField);
  EXPECT_EQ(decode_json(R"({})", m), DecodeResult::kMissingField);
}

TEST(TruthDatagram, JsonWrongTypesGarbageAndTruncation) {
  const std::string full = encode_json(sample());
  Message m = with_flags(0);
  const Message untouched = m;
  const auto replaced = [&](const std::string& from, const std::string& to) {
    std::string s = full;
    s.replace(s.find(from), from.size(), to);
    return s;
  };
  const std::vector<std::string> cases{
      replaced("47.3977", "\"47.3977\""),  // a string
      replaced("47.3977", "null"),
      replaced("47.3977", "true"),
      replaced("47.3977", "[47.3977]"),
      replaced("47.3977", "{\"a\":1}"),
      replaced("47.3977", ".inf"),  // YAML, not JSON
      replaced("47.3977", "NaN"),
      replaced("47.3977", "1e999"),
      replaced("47.3977", "0x10"),
      replaced("47.3977", "+1"),
      replaced("47.3977", "01"),
      replaced("47.3977", "1."),
      replaced("\"h_m\"", "\"lat_deg\""),  // duplicate key
      replaced("\"seq\"", "seq"),          // unquoted key (YAML only)
      full.substr(0, full.size() / 2),     // truncated
      full.substr(0, full.size() - 1),
      full + "}",
      "{",
      "}",
      "[]",
      "{\"seq\":1",
      "{\"seq\":[[[[[[[[[[[[[[[[[[[[]]]]]]]]]]]]]]]]]]]]}",
      "{\"a\": \"}\"",
      "{: }",
      "{\"lat_deg\": &a 1, \"lon_deg\": *a}",  // YAML anchors
      "{\"x\": !!str 1}",
      std::string("{\"seq\":1\0,\"x\":2}", 17),
      "{-- \n\t}",
  };
  for (const std::string& bad : cases) {
    EXPECT_EQ(decode_json(bad, m), DecodeResult::kBadJson) << bad;
  }
  EXPECT_EQ(decode_json("", m), DecodeResult::kBadJson);
  EXPECT_EQ(decode_json("null", m), DecodeResult::kBadJson);
  EXPECT_EQ(decode_json(replaced("\"seq\":17", "\"version\":2,\"seq\":17"), m),
            DecodeResult::kBadVersion);
  // Over 4096 bytes, even with a valid object inside.
  const std::string padded =
      full.substr(0, full.size() - 1) + ",\"pad\":\"" + std::string(4096, 'x') + "\"}";
  EXPECT_EQ(decode_json(padded, m), DecodeResult::kBadLength);
  EXPECT_EQ(decode(bytes_of(padded), m), DecodeResult::kBadLength);
  expect_same(m, untouched);
}

TEST(TruthDatagram, DecodeDispatchesOnTheFirstByte) {
  Message m;
  EXPECT_EQ(decode({}, m), DecodeResult::kBadLength);
  EXPECT_EQ(decode(bytes_of("hello"), m), DecodeResult::kBadMagic);
  EXPECT_EQ(decode(bytes_of(" {\"seq\":1}"), m), DecodeResult::kBadMagic);
  EXPECT_EQ(decode(bytes_of("{\"seq\":1}"), m), DecodeResult::kMissingField);
  EXPECT_EQ(decode(bytes_of("NVTR"), m), DecodeResult::kBadLength);
}

// Random bytes and random mutations of valid datagrams never crash, throw or succeed wrongly.
TEST(TruthDatagram, ArbitraryBytesAreSafe) {
  std::mt19937_64 rng(99);
  const auto bin = encode_binary(sample());
  const std::string json = encode_json(sample());
  for (int i = 0; i < 20000; ++i) {
    std::vector<std::uint8_t> b;
    switch (i % 3) {
      case 0:
        b.resize(rng() % 200);
        for (auto& x : b) x = static_cast<std::uint8_t>(rng());
        if (!b.empty() && rng() % 2 == 0) b[0] = '{';
        break;
      case 1:
        b.assign(bin.begin(), bin.end());
        b[rng() % b.size()] = static_cast<std::uint8_t>(rng());
        break;
      default:
        b.assign(json.begin(), json.end());
        for (int k = static_cast<int>(rng() % 3); k >= 0; --k)
          b[rng() % b.size()] =
              static_cast<std::uint8_t>("{}[]\",:0123456789.eE-+ax\\\n"[rng() % 27]);
        b.resize(b.size() - rng() % 4);
        break;
    }
    Message m;
    EXPECT_NO_THROW({ (void)decode(b, m); });
  }
}

TEST(TruthDatagram, ResultNames) {
  EXPECT_STREQ(to_string(DecodeResult::kOk), "ok");
  EXPECT_STREQ(to_string(DecodeResult::kBadCrc), "bad CRC");
  EXPECT_STREQ(to_string(DecodeResult::kMissingField), "missing or conflicting field");
}

}  // namespace
}  // namespace navemu::truth_datagram
