// UBX codec: checksum and framing against well-known frames; the incremental parser against
// junk, split, back-to-back, interleaved-NMEA, corrupted, oversized and truncated input; the
// typed messages against real receiver captures (u-blox LEA-M8F, NEO-M8T, u-blox 8 GR8013,
// ZED-F9P, ZED-F9T, M10; ../shared/data/receiver_logs): every frame must parse with a good
// checksum, and every message with a typed struct must decode and re-encode to the very same
// bytes. Decoded values are cross-checked against gpsd's own decoding (.chk files) and the
// data README. Randomized input must never crash the parser or a decoder.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <iterator>
#include <limits>
#include <map>
#include <set>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "protocols/ubx.hpp"
#include "protocols/ubx_messages.hpp"

namespace navemu::ubx {
namespace {

using Bytes = std::vector<std::uint8_t>;
using Result = Parser::Result;

// ---- reference data ------------------------------------------------------------------------
// tests/test_support.hpp pulls in the models (Eigen), which this test executable does not link,
// so the lookup of ../shared is repeated here with the same rule: $NAVEMU_SHARED, else the
// directory next to the repository.
std::filesystem::path receiver_logs() {
  const char* env = std::getenv("NAVEMU_SHARED");
  const std::filesystem::path shared = env != nullptr ? env : NAVEMU_SHARED_DEFAULT;
  return shared / "data" / "receiver_logs";
}

#define REQUIRE_CAPTURE(path)                                               \
  do {                                                                      \
    if (!std::filesystem::is_regular_file(path))                            \
      GTEST_SKIP() << (path) << " not found (set NAVEMU_SHARED): skipped"; \
  } while (0)

// The receiver byte stream of a capture: gpsd's .log files start with '#' comment lines, which
// are dropped (only the leading ones: UBX payloads may contain '#').
Bytes read_capture(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  Bytes data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (path.extension() != ".log") return data;
  std::size_t start = 0;
  while (start < data.size() && data[start] == '#') {
    const auto nl = std::find(data.begin() + static_cast<std::ptrdiff_t>(start), data.end(), '\n');
    start = nl == data.end() ? data.size() : static_cast<std::size_t>(nl - data.begin()) + 1;
  }
  return Bytes(data.begin() + static_cast<std::ptrdiff_t>(start), data.end());
}

struct Frame {
  MsgId msg;
  Bytes payload;
};

struct Parsed {
  std::vector<Frame> frames;
  std::vector<Result> results;  // every result other than kNeedMore, in order
  Parser::Counters counters;
  std::size_t buffered = 0;  // an unfinished frame at the end of the input
  std::map<std::pair<int, int>, int> count;  // (class, id) -> frames
  int of(MsgId m) const {
    const auto it = count.find({m.cls, m.id});
    return it == count.end() ? 0 : it->second;
  }
};

Parsed parse_all(std::span<const std::uint8_t> bytes, std::size_t max_payload = 4096) {
  Parser parser(max_payload);
  Parsed out;
  parser.feed(bytes, [&](Result r) {
    out.results.push_back(r);
    if (r != Result::kFrame) return;
    out.frames.push_back({{parser.cls(), parser.id()},
                          Bytes(parser.payload().begin(), parser.payload().end())});
    ++out.count[{parser.cls(), parser.id()}];
  });
  EXPECT_FALSE(parser.pending());
  out.counters = parser.counters();
  out.buffered = parser.buffered();
  return out;
}

Bytes frame_of(MsgId m, const Bytes& payload) {
  Bytes out;
  append_frame(m.cls, m.id, payload, out);
  return out;
}

Bytes concat(std::initializer_list<Bytes> parts) {
  Bytes out;
  for (const Bytes& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

Bytes ascii(const std::string& s) { return Bytes(s.begin(), s.end()); }

// Bytes accounted for by good frames.
std::uint64_t frame_bytes(const Parsed& p) {
  std::uint64_t n = 0;
  for (const Frame& f : p.frames) n += f.payload.size() + kFrameOverhead;
  return n;
}

// ---- checksum and framing ------------------------------------------------------------------

TEST(UbxFraming, ChecksumOfWellKnownPolls) {
  // MON-VER poll and CFG-PRT poll as gpsd sends them while probing.
  Bytes out;
  append_poll(kMonVer, out);
  EXPECT_EQ(out, (Bytes{0xB5, 0x62, 0x0A, 0x04, 0x00, 0x00, 0x0E, 0x34}));
  out.clear();
  append_poll(kCfgPrt, out);
  EXPECT_EQ(out, (Bytes{0xB5, 0x62, 0x06, 0x00, 0x00, 0x00, 0x06, 0x18}));
  out.clear();
  append_poll(kCfgRate, out);
  EXPECT_EQ(out, (Bytes{0xB5, 0x62, 0x06, 0x08, 0x00, 0x00, 0x0E, 0x30}));
  // CFG-MSG, 3-byte form: NAV-PVT once per solution on the current port.
  out.clear();
  append(CfgMsgCurrentPort{0x01, 0x07, 1}, out);
  EXPECT_EQ(out, (Bytes{0xB5, 0x62, 0x06, 0x01, 0x03, 0x00, 0x01, 0x07, 0x01, 0x13, 0x51}));

  const Bytes body{0x0A, 0x04, 0x00, 0x00};
  EXPECT_EQ(checksum(body), (std::array<std::uint8_t, 2>{0x0E, 0x34}));
  EXPECT_EQ(checksum({}), (std::array<std::uint8_t, 2>{0x00, 0x00}));
}

TEST(UbxFraming, WriterReaderLittleEndianAndBounds) {
  Bytes b;
  Writer w(b);
  w.u1(0x01);
  w.i2(-2);
  w.u4(0x04030201);
  w.r4(1.5f);
  w.r8(-0.25);
  ASSERT_EQ(b.size(), 1u + 2 + 4 + 4 + 8);
  EXPECT_EQ(b[1], 0xFE);
  EXPECT_EQ(b[2], 0xFF);
  EXPECT_EQ(b[3], 0x01);
  EXPECT_EQ(b[6], 0x04);
  const Reader r(b);
  EXPECT_EQ(r.i2(1), -2);
  EXPECT_EQ(r.u4(3), 0x04030201u);
  EXPECT_EQ(r.r4(7), 1.5f);
  EXPECT_EQ(r.r8(11), -0.25);
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(r.u4(17), 0u);  // past the end
  EXPECT_FALSE(r.ok());
  const Reader r2(b);
  EXPECT_EQ(r2.r8(12), 0.0);
  EXPECT_EQ(r2.u1(19), 0u);
  EXPECT_EQ(r2.u2(static_cast<std::size_t>(-1)), 0u);  // offset overflow is caught
  EXPECT_FALSE(r2.ok());
}

TEST(UbxFraming, OversizedPayloadIsNotFramed) {
  Bytes out{0x42};
  const Bytes big(kMaxWirePayload + 1, 0);
  append_frame(0x01, 0x02, big, out);
  EXPECT_EQ(out, Bytes{0x42});
  const std::size_t start = begin_frame(0x01, 0x02, out);
  out.resize(out.size() + kMaxWirePayload + 1);
  EXPECT_FALSE(end_frame(start, out));
  EXPECT_EQ(out, Bytes{0x42});
  const Bytes max(kMaxWirePayload, 7);
  append_frame(0x01, 0x02, max, out);
  EXPECT_EQ(out.size(), 1 + kMaxWirePayload + kFrameOverhead);
}

// ---- parser --------------------------------------------------------------------------------

Bytes sample_frame(std::uint8_t id, std::size_t n, std::uint8_t seed) {
  Bytes payload(n);
  for (std::size_t i = 0; i < n; ++i) payload[i] = static_cast<std::uint8_t>(seed + 31 * i);
  return frame_of({0x01, id}, payload);
}

TEST(UbxParser, SkipsJunkAndFindsFrame) {
  const Bytes junk = ascii("hello \x01\x02\xFF world");
  const Bytes f = sample_frame(0x07, 92, 3);
  const Parsed p = parse_all(concat({junk, f, junk}));
  ASSERT_EQ(p.frames.size(), 1u);
  EXPECT_EQ(frame_of(p.frames[0].msg, p.frames[0].payload), f);
  EXPECT_EQ(p.counters.junk_bytes, 2 * junk.size());
  EXPECT_EQ(p.counters.checksum_errors, 0u);
}

TEST(UbxParser, FrameSplitAtEveryPosition) {
  const Bytes f = sample_frame(0x35, 40, 9);
  for (std::size_t cut = 0; cut <= f.size(); ++cut) {
    Parser parser;
    int frames = 0;
    parser.feed(std::span<const std::uint8_t>(f).first(cut), [&](Result r) {
      frames += r == Result::kFrame;
    });
    EXPECT_EQ(frames, cut == f.size() ? 1 : 0) << cut;
    parser.feed(std::span<const std::uint8_t>(f).subspan(cut), [&](Result r) {
      frames += r == Result::kFrame;
      EXPECT_EQ(parser.payload().size(), 40u);
    });
    EXPECT_EQ(frames, 1) << cut;
  }
}

TEST(UbxParser, ByteAtATimeResults) {
  // One result per byte: kNeedMore until the last checksum byte, then kFrame with the payload.
  const Bytes f = frame_of(kAckAck, {0x06, 0x01});
  Parser parser;
  for (std::size_t i = 0; i + 1 < f.size(); ++i) EXPECT_EQ(parser.feed(f[i]), Result::kNeedMore);
  ASSERT_EQ(parser.feed(f.back()), Result::kFrame);
  EXPECT_EQ(parser.cls(), 0x05);
  EXPECT_EQ(parser.id(), 0x01);
  EXPECT_EQ(Bytes(parser.payload().begin(), parser.payload().end()), (Bytes{0x06, 0x01}));
  EXPECT_FALSE(parser.pending());
}

TEST(UbxParser, BackToBackAndEmptyPayloads) {
  const Bytes a = sample_frame(0x01, 20, 1);
  const Bytes b = frame_of(kMonVer, {});
  const Bytes c = sample_frame(0x07, 92, 2);
  const Parsed p = parse_all(concat({a, b, c, b}));
  ASSERT_EQ(p.frames.size(), 4u);
  EXPECT_EQ(frame_of(p.frames[0].msg, p.frames[0].payload), a);
  EXPECT_EQ(p.frames[1].msg, kMonVer);
  EXPECT_TRUE(p.frames[1].payload.empty());
  EXPECT_EQ(frame_of(p.frames[2].msg, p.frames[2].payload), c);
  EXPECT_EQ(p.counters.junk_bytes, 0u);
}

TEST(UbxParser, InterleavedNmea) {
  const Bytes gga = ascii(
      "$GPGGA,212757.00,4404.1318940,N,12118.8457360,W,1,00,0.79,1130.02,M,-22.154,M,,*6A\r\n");
  const Bytes rmc = ascii(
      "$GPRMC,212757.00,A,4404.1318940,N,12118.8457360,W,0.0875,120.452,100620,14.4,E*42\r\n");
  const Bytes f1 = sample_frame(0x07, 92, 5);
  const Bytes f2 = sample_frame(0x35, 8 + 12 * 3, 6);
  const Parsed p = parse_all(concat({gga, f1, rmc, f2, gga}));
  ASSERT_EQ(p.frames.size(), 2u);
  EXPECT_EQ(p.counters.junk_bytes, 2 * gga.size() + rmc.size());
}

TEST(UbxParser, GpsdProbeStringsAreSkipped) {
  // What gpsd writes while hunting (other vendors' probes, binary blobs), followed by the two
  // UBX polls it sends: only the polls are frames. A device reading its input sees this mix.
  const Bytes probes = concat({
      ascii("$PASHQ,RID*28\r\n"),
      ascii("@F0.3=1*67\r\n"),
      ascii("$PSRF100,0,9600,8,1,0*0C\r\n"),
      ascii("$PMTK605*31\r\n"),
      Bytes{0xA0, 0xA2, 0x00, 0x02, 0x84, 0x00, 0x00, 0x84, 0xB0, 0xB3},  // SiRF binary
      Bytes{0x10, 0x1F, 0x10, 0x03},                                      // TSIP-style DLE
      Bytes{0xB5, 0xB5, 0xB5},                                            // stray sync bytes
  });
  Bytes polls;
  append_poll(kMonVer, polls);
  append_poll(kCfgPrt, polls);
  const Parsed p = parse_all(concat({probes, polls, probes}));
  ASSERT_EQ(p.frames.size(), 2u);
  EXPECT_EQ(p.frames[0].msg, kMonVer);
  EXPECT_EQ(p.frames[1].msg, kCfgPrt);
  EXPECT_EQ(p.counters.checksum_errors, 0u);
  EXPECT_EQ(p.counters.too_long, 0u);
  // The last 0xB5 may still start a frame: it is held, not dropped.
  EXPECT_EQ(p.buffered, 1u);
  EXPECT_EQ(p.counters.junk_bytes, 2 * probes.size() - 1);
}

TEST(UbxParser, BadChecksumIsCountedAndNextFrameFound) {
  Bytes bad = sample_frame(0x07, 92, 7);
  bad[20] ^= 0x40;
  const Bytes good = sample_frame(0x04, 18, 8);
  const Parsed p = parse_all(concat({bad, good}));
  ASSERT_EQ(p.frames.size(), 1u);
  EXPECT_EQ(frame_of(p.frames[0].msg, p.frames[0].payload), good);
  EXPECT_EQ(p.counters.checksum_errors, 1u);
  EXPECT_EQ(p.results.front(), Result::kChecksumError);
  EXPECT_EQ(p.counters.junk_bytes, bad.size());
}

TEST(UbxParser, OversizedLengthIsCountedAndResynchronised) {
  // A length above max_payload: dropped at once, and the following frame is found; the bytes
  // after the false sync are scanned again, so a frame starting in them is not lost.
  const Bytes f = sample_frame(0x07, 92, 11);
  const Bytes oversized{0xB5, 0x62, 0x01, 0x07, 0xFF, 0x7F};
  const Parsed p = parse_all(concat({oversized, f}), 1024);
  ASSERT_EQ(p.frames.size(), 1u);
  EXPECT_EQ(p.counters.too_long, 1u);
  EXPECT_EQ(p.results.front(), Result::kTooLong);
  EXPECT_EQ(p.counters.junk_bytes, oversized.size());

  // A false sync whose "class" byte starts a real frame: B5 62 B5 62 ...
  const Parsed q = parse_all(concat({Bytes{0xB5, 0x62}, f}), 1024);
  ASSERT_EQ(q.frames.size(), 1u);
  EXPECT_EQ(frame_of(q.frames[0].msg, q.frames[0].payload), f);
}

TEST(UbxParser, TruncatedFrameFollowedByGoodOnes) {
  // A frame cut short (e.g. by a receiver reset): its length swallows the next frames, its
  // checksum then fails, and the replay of the swallowed bytes finds both good frames.
  Bytes cut = sample_frame(0x07, 92, 13);
  cut.resize(6 + 40);
  const Bytes g1 = sample_frame(0x01, 20, 14);
  const Bytes g2 = sample_frame(0x35, 8 + 12 * 9, 15);
  const Bytes g3 = frame_of(kNavEoe, {1, 2, 3, 4});
  const Bytes all = concat({cut, g1, g2, g3});
  const Parsed p = parse_all(all);
  ASSERT_EQ(p.frames.size(), 3u);
  EXPECT_EQ(frame_of(p.frames[0].msg, p.frames[0].payload), g1);
  EXPECT_EQ(frame_of(p.frames[1].msg, p.frames[1].payload), g2);
  EXPECT_EQ(frame_of(p.frames[2].msg, p.frames[2].payload), g3);
  EXPECT_EQ(p.counters.checksum_errors, 1u);
  EXPECT_EQ(p.counters.junk_bytes, cut.size());
  EXPECT_EQ(frame_bytes(p) + p.counters.junk_bytes, all.size());

  // Byte-at-a-time without draining: the pending bytes are handled as later bytes arrive, so
  // a caller that only ever calls feed(byte) still sees every frame once the stream goes on.
  Parser parser;
  int frames = 0;
  for (const std::uint8_t b : concat({all, Bytes(200, 0x00)}))
    frames += parser.feed(b) == Result::kFrame;
  EXPECT_EQ(frames, 3);
  EXPECT_FALSE(parser.pending());
}

TEST(UbxParser, ResetForgetsPartialFrame) {
  const Bytes f = sample_frame(0x07, 92, 17);
  Parser parser;
  for (std::size_t i = 0; i < 50; ++i) parser.feed(f[i]);
  parser.reset();
  int frames = 0;
  parser.feed(f, [&](Result r) { frames += r == Result::kFrame; });
  EXPECT_EQ(frames, 1);
}

TEST(UbxParser, RandomJunkAroundFramesNeverLosesAFrame) {
  // Frames embedded in random bytes (which contain false syncs with random lengths and bad
  // checksums): every embedded frame is found, in order, and every byte is accounted for.
  std::mt19937 rng(20240611);
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_int_distribution<int> junk_len(0, 300);
  std::uniform_int_distribution<int> payload_len(0, 600);
  for (int trial = 0; trial < 40; ++trial) {
    Bytes stream;
    std::vector<Bytes> embedded;
    for (int k = 0; k < 30; ++k) {
      const int nj = junk_len(rng);
      for (int i = 0; i < nj; ++i) {
        // Plenty of sync pairs so that false candidates overlap the real frames.
        if (byte(rng) < 12) {
          stream.push_back(kSync1);
          stream.push_back(kSync2);
        } else {
          stream.push_back(static_cast<std::uint8_t>(byte(rng)));
        }
      }
      Bytes payload(static_cast<std::size_t>(payload_len(rng)));
      for (auto& b : payload) b = static_cast<std::uint8_t>(byte(rng));
      embedded.push_back(frame_of({0x01, static_cast<std::uint8_t>(k)}, payload));
      stream.insert(stream.end(), embedded.back().begin(), embedded.back().end());
    }
    // A false candidate open at the end may still hold the last frames: more input (longer
    // than any candidate) lets it fail and the replay find them.
    stream.insert(stream.end(), 1024 + kFrameOverhead, 0x00);
    const Parsed p = parse_all(stream, 1024);
    std::size_t next = 0;
    for (const Frame& f : p.frames)
      if (next < embedded.size() && frame_of(f.msg, f.payload) == embedded[next]) ++next;
    EXPECT_EQ(next, embedded.size()) << "trial " << trial;
    EXPECT_EQ(p.buffered, 0u);
    EXPECT_EQ(frame_bytes(p) + p.counters.junk_bytes, stream.size()) << "trial " << trial;
  }
}

TEST(UbxParser, DenseFalseSyncsWithMaximalLengths) {
  // Worst case for the replay: a false sync with the largest accepted length every six bytes,
  // so that every byte lies inside many failing candidates; real frames in between are still
  // all found, and the ring (max_payload + 16 bytes) never overflows.
  constexpr std::size_t kMax = 16;
  const Bytes false_sync{kSync1, kSync2, 0x01, 0x02, static_cast<std::uint8_t>(kMax), 0x00};
  Bytes stream;
  std::vector<Bytes> embedded;
  for (int k = 0; k < 50; ++k) {
    for (int i = 0; i < k % 7; ++i)
      stream.insert(stream.end(), false_sync.begin(), false_sync.end());
    const auto id = static_cast<std::uint8_t>(k);
    embedded.push_back(sample_frame(id, static_cast<std::size_t>(k) % (kMax + 1), id));
    stream.insert(stream.end(), embedded.back().begin(), embedded.back().end());
  }
  stream.insert(stream.end(), kMax + kFrameOverhead, 0x00);
  const Parsed p = parse_all(stream, kMax);
  std::size_t next = 0;
  for (const Frame& f : p.frames)
    if (next < embedded.size() && frame_of(f.msg, f.payload) == embedded[next]) ++next;
  EXPECT_EQ(next, embedded.size());
  EXPECT_EQ(frame_bytes(p) + p.counters.junk_bytes, stream.size());
  EXPECT_GT(p.counters.checksum_errors, 0u);
}

TEST(UbxParser, RandomBytesNeverCrash) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> byte(0, 255);
  Bytes stream(1 << 20);
  for (auto& b : stream) b = static_cast<std::uint8_t>(byte(rng) < 8 ? kSync1 : byte(rng));
  for (const std::size_t max_payload : {std::size_t{0}, std::size_t{16}, std::size_t{4096}}) {
    const Parsed p = parse_all(stream, max_payload);
    EXPECT_EQ(frame_bytes(p) + p.counters.junk_bytes + p.buffered, stream.size());
  }
}

// ---- typed messages: hand-made vectors -----------------------------------------------------

template <typename T>
Bytes encoded(const T& m) {
  Bytes out;
  append(m, out);
  return out;
}

// Decodes the payload of a frame made by append().
template <typename T>
bool decode_frame(const Bytes& f, T& m) {
  if (f.size() < kFrameOverhead) return false;
  return decode(std::span<const std::uint8_t>(f).subspan(6, f.size() - kFrameOverhead), m);
}

TEST(UbxMessages, CfgPrtFromUbxtool) {
  // ubxtool -S 115200: UART1, 8N1, 115200 Bd, UBX+NMEA in and out.
  const Bytes payload{0x01, 0x00, 0x00, 0x00, 0xC0, 0x08, 0x00, 0x00, 0x00, 0xC2,
                      0x01, 0x00, 0x03, 0x00, 0x03, 0x00, 0x00, 0x00, 0x00, 0x00};
  CfgPrt prt;
  ASSERT_TRUE(decode(payload, prt));
  EXPECT_EQ(prt.port_id, kPortUart1);
  EXPECT_EQ(prt.mode, CfgPrt::kMode8N1);
  EXPECT_EQ(prt.baud_rate, 115200u);
  EXPECT_EQ(prt.in_proto_mask, kProtoUbx | kProtoNmea);
  EXPECT_EQ(prt.out_proto_mask, kProtoUbx | kProtoNmea);
  EXPECT_EQ(encoded(prt), frame_of(kCfgPrt, payload));

  CfgPrtPoll poll;
  ASSERT_TRUE(decode({}, poll));
  EXPECT_FALSE(poll.has_port_id);
  const Bytes one{kPortUsb};
  ASSERT_TRUE(decode(one, poll));
  EXPECT_TRUE(poll.has_port_id);
  EXPECT_EQ(poll.port_id, kPortUsb);
  EXPECT_EQ(encoded(poll), frame_of(kCfgPrt, one));
  EXPECT_FALSE(decode(payload, poll));
  EXPECT_FALSE(decode(one, prt));
}

TEST(UbxMessages, CfgMsgThreeForms) {
  const Bytes two{0x01, 0x07}, three{0x01, 0x07, 0x01},
      eight{0xF0, 0x00, 0x00, 0x01, 0x00, 0x01, 0x00, 0x00};
  CfgMsgPoll poll;
  CfgMsgCurrentPort cur;
  CfgMsg all;
  EXPECT_TRUE(decode(two, poll));
  EXPECT_FALSE(decode(three, poll));
  EXPECT_TRUE(decode(three, cur));
  EXPECT_FALSE(decode(two, cur));
  EXPECT_EQ(cur.rate, 1);
  ASSERT_TRUE(decode(eight, all));
  EXPECT_FALSE(decode(three, all));
  EXPECT_EQ(all.msg_class, kClassNmea);
  EXPECT_EQ(all.rate[kPortUart1], 1);
  EXPECT_EQ(all.rate[kPortUsb], 1);
  EXPECT_EQ(encoded(poll), frame_of(kCfgMsg, two));
  EXPECT_EQ(encoded(cur), frame_of(kCfgMsg, three));
  EXPECT_EQ(encoded(all), frame_of(kCfgMsg, eight));
}

TEST(UbxMessages, CfgRateNav5GnssCfgRst) {
  // ubxtool -p CFG-RATE,100,1 (timeRef 1 = GPS).
  const Bytes rate_payload{0x64, 0x00, 0x01, 0x00, 0x01, 0x00};
  CfgRate rate;
  ASSERT_TRUE(decode(rate_payload, rate));
  EXPECT_EQ(rate.meas_rate_ms, 100);
  EXPECT_EQ(rate.nav_rate_cycles, 1);
  EXPECT_EQ(rate.time_ref, CfgRate::kTimeRefGps);
  EXPECT_EQ(encoded(rate), frame_of(kCfgRate, rate_payload));
  EXPECT_FALSE(decode({}, rate));

  // ubxtool -p MODEL,4: mask = dyn only, dynModel 4, the rest zero.
  Bytes nav5_payload(36, 0);
  nav5_payload[0] = 0x01;
  nav5_payload[2] = 4;
  CfgNav5 nav5;
  ASSERT_TRUE(decode(nav5_payload, nav5));
  EXPECT_EQ(nav5.mask, CfgNav5::kMaskDyn);
  EXPECT_EQ(nav5.dyn_model, CfgNav5::kDynAutomotive);
  EXPECT_EQ(encoded(nav5), frame_of(kCfgNav5, nav5_payload));
  CfgNav5 nav5b;
  nav5b.fixed_alt_cm = -12345;
  nav5b.min_elev_deg = -5;
  nav5b.static_hold_max_dist_m = 200;
  nav5b.reserved2 = {1, 2, 3, 4, 5};
  CfgNav5 back;
  ASSERT_TRUE(decode_frame(encoded(nav5b), back));
  EXPECT_EQ(back.fixed_alt_cm, -12345);
  EXPECT_EQ(back.min_elev_deg, -5);
  EXPECT_EQ(back.static_hold_max_dist_m, 200);
  EXPECT_EQ(encoded(back), encoded(nav5b));

  CfgGnss gnss;
  gnss.msg_ver = 0;
  gnss.num_trk_ch_hw = 32;
  gnss.num_trk_ch_use = 32;
  gnss.blocks = {{0, 8, 16, 0, 0x01010001}, {6, 8, 14, 0, 0x01010001}};
  const Bytes gf = encoded(gnss);
  EXPECT_EQ(gf.size(), kFrameOverhead + 4 + 16);
  CfgGnss gback;
  ASSERT_TRUE(decode_frame(gf, gback));
  ASSERT_EQ(gback.blocks.size(), 2u);
  EXPECT_EQ(gback.blocks[1].gnss_id, 6);
  EXPECT_EQ(gback.blocks[1].flags, 0x01010001u);
  EXPECT_EQ(encoded(gback), gf);
  Bytes short_gnss(gf.begin() + 6, gf.end() - 3);
  EXPECT_FALSE(decode(short_gnss, gback));

  // ubxtool's CFG-CFG (13 bytes) and the 12-byte form.
  const Bytes cfg13{0x1F, 0x0F, 0, 0, 0, 0, 0, 0, 0x1F, 0x0F, 0, 0, 0x17};
  CfgCfg cfg;
  ASSERT_TRUE(decode(cfg13, cfg));
  EXPECT_EQ(cfg.clear_mask, 0x0F1Fu);
  EXPECT_TRUE(cfg.has_device_mask);
  EXPECT_EQ(cfg.device_mask, 0x17);
  EXPECT_EQ(encoded(cfg), frame_of(kCfgCfg, cfg13));
  const Bytes cfg12(cfg13.begin(), cfg13.end() - 1);
  ASSERT_TRUE(decode(cfg12, cfg));
  EXPECT_FALSE(cfg.has_device_mask);
  EXPECT_EQ(encoded(cfg), frame_of(kCfgCfg, cfg12));
  EXPECT_FALSE(decode(Bytes(14, 0), cfg));

  const Bytes rst{0xFF, 0xFF, 0x01, 0x00};  // cold start, controlled software reset
  CfgRst r;
  ASSERT_TRUE(decode(rst, r));
  EXPECT_EQ(r.nav_bbr_mask, CfgRst::kColdStart);
  EXPECT_EQ(r.reset_mode, CfgRst::kControlledSoftwareReset);
  EXPECT_EQ(encoded(r), frame_of(kCfgRst, rst));
}

TEST(UbxMessages, ConfigurationKeys) {
  // Key sizes from bits 28..30 (ubxtool and pyubx2 give the same IDs and types).
  static_assert(cfg_value_size(cfgkey::kRateMeas) == 2);
  static_assert(cfg_value_size(cfgkey::kRateNav) == 2);
  static_assert(cfg_value_size(cfgkey::kMsgoutUbxNavPvtUart1) == 1);
  static_assert(cfg_value_size(cfgkey::kMsgoutUbxNavPvtUsb) == 1);
  static_assert(cfg_value_size(cfgkey::kUart1Baudrate) == 4);
  static_assert(cfg_value_size(cfgkey::kUart1outprotNmea) == 1);
  static_assert(cfg_value_size(cfgkey::kUart1outprotUbx) == 1);
  static_assert(cfg_value_size(cfgkey::kUart1inprotUbx) == 1);
  static_assert(cfg_value_size(cfgkey::kUart1inprotNmea) == 1);
  static_assert(cfg_value_size(0x50C70004) == 8);
  static_assert(cfg_value_size(0x00000000) == 0);
  static_assert(cfg_value_size(0x60000001) == 0);
  static_assert(cfgkey::kRateMeas == 0x30210001 && cfgkey::kRateNav == 0x30210002);
  static_assert(cfgkey::kMsgoutUbxNavPvtUart1 == 0x20910007);
  static_assert(cfgkey::kMsgoutUbxNavPvtUsb == 0x20910009);
  static_assert(cfgkey::kUart1Baudrate == 0x40520001);
  static_assert(cfgkey::kUart1outprotUbx == 0x10740001);
  static_assert(cfgkey::kUart1outprotNmea == 0x10740002);
  static_assert(cfgkey::kUart1inprotUbx == 0x10730001);
  static_assert(cfgkey::kUart1inprotNmea == 0x10730002);

  // ubxtool -P 27 -z CFG-RATE-MEAS,200 (VALSET version 0, layers 7 by default; the key's
  // value is a U2).
  const Bytes valset_payload{0x00, 0x07, 0x00, 0x00, 0x01, 0x00, 0x21, 0x30, 0xC8, 0x00};
  CfgValset set;
  ASSERT_TRUE(decode(valset_payload, set));
  EXPECT_EQ(set.layers, kLayerMaskRam | kLayerMaskBbr | kLayerMaskFlash);
  ASSERT_EQ(set.values.size(), 1u);
  EXPECT_EQ(set.values[0], (CfgKeyValue{cfgkey::kRateMeas, 200}));
  EXPECT_EQ(encoded(set), frame_of(kCfgValset, valset_payload));

  // Several sizes in one message, version 1 with a transaction.
  CfgValset multi;
  multi.version = 1;
  multi.transaction = 1;
  multi.values = {{cfgkey::kUart1Baudrate, 115200},
                  {cfgkey::kUart1outprotNmea, 0},
                  {cfgkey::kMsgoutUbxNavPvtUart1, 1},
                  {0x50C70004, 0x0102030405060708}};
  const Bytes mf = encoded(multi);
  EXPECT_EQ(mf.size(), kFrameOverhead + 4 + (4 + 4) + (4 + 1) + (4 + 1) + (4 + 8));
  CfgValset mback;
  ASSERT_TRUE(decode_frame(mf, mback));
  EXPECT_EQ(mback.values, multi.values);
  EXPECT_EQ(mback.transaction, 1);
  // A truncated value, a reserved size code, and an unknown version are rejected.
  EXPECT_FALSE(decode(Bytes(valset_payload.begin(), valset_payload.end() - 1), set));
  Bytes reserved_size = valset_payload;
  reserved_size[7] = 0x70;
  EXPECT_FALSE(decode(reserved_size, set));
  Bytes v2 = valset_payload;
  v2[0] = 2;
  EXPECT_FALSE(decode(v2, set));

  // ubxtool -g CFG-RATE-MEAS: VALGET request version 0, then the answer version 1.
  const Bytes get_payload{0x00, 0x00, 0x00, 0x00, 0x01, 0x00, 0x21, 0x30};
  CfgValgetRequest get;
  ASSERT_TRUE(decode(get_payload, get));
  EXPECT_EQ(get.layer, kLayerRam);
  EXPECT_EQ(get.keys, (std::vector<std::uint32_t>{cfgkey::kRateMeas}));
  EXPECT_EQ(encoded(get), frame_of(kCfgValget, get_payload));
  CfgValgetResponse wrong_version;
  EXPECT_FALSE(decode(get_payload, wrong_version));
  EXPECT_FALSE(decode(Bytes{0, 0, 0, 0, 1, 0, 0x21}, get));

  CfgValgetResponse ans;
  ans.values = {{cfgkey::kRateMeas, 1000}, {cfgkey::kRateNav, 1}};
  const Bytes af = encoded(ans);
  EXPECT_EQ(af, frame_of(kCfgValget, Bytes{0x01, 0x00, 0x00, 0x00, 0x01, 0x00, 0x21, 0x30, 0xE8,
                                           0x03, 0x02, 0x00, 0x21, 0x30, 0x01, 0x00}));
  CfgValgetResponse aback;
  ASSERT_TRUE(decode_frame(af, aback));
  EXPECT_EQ(aback.values, ans.values);
  CfgValgetRequest wrong_request;
  EXPECT_FALSE(decode_frame(af, wrong_request));

  // ubxtool's VALDEL: version 0, layers BBR + flash, keys.
  const Bytes del_payload{0x00, 0x06, 0x00, 0x00, 0x01, 0x00, 0x21, 0x30};
  CfgValdel del;
  ASSERT_TRUE(decode(del_payload, del));
  EXPECT_EQ(del.layers, kLayerMaskBbr | kLayerMaskFlash);
  EXPECT_EQ(del.keys, (std::vector<std::uint32_t>{cfgkey::kRateMeas}));
  EXPECT_EQ(encoded(del), frame_of(kCfgValdel, del_payload));
}

TEST(UbxMessages, MonVerStringsAndProtver) {
  MonVer v;
  v.sw_version = "EXT CORE 1.00 (emulated)";
  v.hw_version = "00190000";
  v.extensions = {"ROM BASE 0x118B2060", "FWVER=HPG 1.32", "PROTVER=27.31",
                  std::string(40, 'x')};
  const Bytes f = encoded(v);
  EXPECT_EQ(f.size(), kFrameOverhead + 40 + 4 * 30);
  MonVer back;
  ASSERT_TRUE(decode_frame(f, back));
  EXPECT_EQ(back.sw_version, v.sw_version);
  EXPECT_EQ(back.hw_version, v.hw_version);
  ASSERT_EQ(back.extensions.size(), 4u);
  EXPECT_EQ(back.extensions[3], std::string(29, 'x'));  // truncated, NUL kept
  EXPECT_EQ(protocol_version_x100(back), 2731);

  MonVer old;
  old.extensions = {"PROTVER 16.00"};
  EXPECT_EQ(protocol_version_x100(old), 1600);
  old.extensions = {"PROTVER=34.1"};
  EXPECT_EQ(protocol_version_x100(old), 3410);
  old.extensions = {"FWVER=SPG 3.01", "PROTVER=18"};
  EXPECT_EQ(protocol_version_x100(old), 1800);
  old.extensions = {"PROTVERX"};
  EXPECT_EQ(protocol_version_x100(old), 0);
  EXPECT_FALSE(decode(Bytes(39, 0), back));
  EXPECT_FALSE(decode(Bytes(41, 0), back));
}

TEST(UbxMessages, NavAndRxmRoundTripByHand) {
  NavPvt pvt;
  pvt.i_tow_ms = 123456789;
  pvt.lon_1e7deg = -1213140956;
  pvt.lat_1e7deg = 440688649;
  pvt.height_mm = 1108672;
  pvt.vel_d_mmps = -111;
  pvt.head_veh_1e5deg = -1;
  pvt.mag_dec_1e2deg = -1440;
  const Bytes f = encoded(pvt);
  ASSERT_EQ(f.size(), kFrameOverhead + NavPvt::kPayloadSize);
  NavPvt back;
  ASSERT_TRUE(decode_frame(f, back));
  EXPECT_EQ(back.lon_1e7deg, pvt.lon_1e7deg);
  EXPECT_EQ(back.vel_d_mmps, -111);
  EXPECT_EQ(back.mag_dec_1e2deg, -1440);
  EXPECT_EQ(encoded(back), f);
  // Shorter payloads are rejected; a longer one (a later protocol's extension) is accepted.
  Bytes payload(f.begin() + 6, f.end() - 2);
  EXPECT_FALSE(decode(std::span<const std::uint8_t>(payload).first(91), back));
  payload.push_back(0xAA);
  EXPECT_TRUE(decode(payload, back));

  RxmRawx rawx;
  rawx.rcv_tow_s = 507601.9990;
  rawx.week = 2110;
  rawx.leap_s = 18;
  rawx.version = 1;
  RxmRawxMeas m;
  m.pr_mes_m = 2.1e7 + 0.123;
  m.cp_mes_cycles = -1.1e8;
  m.do_mes_hz = -1234.5f;
  m.sv_id = 12;
  m.locktime_ms = 64500;
  m.cno_dbhz = 45;
  m.trk_stat = RxmRawxMeas::kPrValid | RxmRawxMeas::kCpValid;
  rawx.meas = {m, m};
  const Bytes rf = encoded(rawx);
  ASSERT_EQ(rf.size(), kFrameOverhead + 16 + 64);
  RxmRawx rback;
  ASSERT_TRUE(decode_frame(rf, rback));
  ASSERT_EQ(rback.meas.size(), 2u);
  EXPECT_EQ(rback.meas[1].pr_mes_m, m.pr_mes_m);
  EXPECT_EQ(rback.meas[1].do_mes_hz, m.do_mes_hz);
  EXPECT_EQ(encoded(rback), rf);
  Bytes rp(rf.begin() + 6, rf.end() - 2);
  rp.push_back(0);  // numMeas says 2: 81 bytes do not fit
  EXPECT_FALSE(decode(rp, rback));

  RxmSfrbx sf;
  sf.words = std::vector<std::uint32_t>(10, 0x22C03D38);
  const Bytes sff = encoded(sf);
  EXPECT_EQ(sff.size(), kFrameOverhead + 8 + 40);
  RxmSfrbx sback;
  ASSERT_TRUE(decode_frame(sff, sback));
  EXPECT_EQ(sback.words, sf.words);

  NavSat sat;
  sat.svs.resize(300);  // the count is one byte: 255 are sent
  const Bytes satf = encoded(sat);
  EXPECT_EQ(satf.size(), kFrameOverhead + 8 + 12 * 255);

  MonHw hw;
  hw.agc_cnt = 4000;
  hw.vp[16] = 0x42;
  hw.jam_ind = 7;
  hw.pull_l = 0xDEADBEEF;
  const Bytes hwf = encoded(hw);
  EXPECT_EQ(hwf.size(), kFrameOverhead + 60);
  MonHw hback;
  ASSERT_TRUE(decode_frame(hwf, hback));
  EXPECT_EQ(hback.vp[16], 0x42);
  EXPECT_EQ(hback.jam_ind, 7);
  EXPECT_EQ(hback.pull_l, 0xDEADBEEFu);
  EXPECT_EQ(encoded(hback), hwf);

  AckAck ack{0x06, 0x8A};
  EXPECT_EQ(encoded(ack), frame_of(kAckAck, Bytes{0x06, 0x8A}));
  AckNak nak{0x06, 0x01};
  EXPECT_EQ(encoded(nak), frame_of(kAckNak, Bytes{0x06, 0x01}));
}

// ---- real captures -------------------------------------------------------------------------

// Decodes a frame into T and appends it again; true when the bytes are the received ones.
template <typename T>
bool reencodes(const Frame& f, T& m) {
  if (!decode(f.payload, m)) return false;
  Bytes out;
  append(m, out);
  return out == frame_of(f.msg, f.payload);
}

// Round trip of every frame whose message has a struct; counts per message name.
struct RoundTrip {
  std::map<std::string, int> ok, failed;
  std::set<std::pair<int, int>> handled;  // class and id of the messages with a struct
};

RoundTrip round_trip_all(const std::vector<Frame>& frames) {
  RoundTrip rt;
  const Frame* current = nullptr;
  const auto check = [&](const char* name, bool good) {
    ++(good ? rt.ok : rt.failed)[name];
    rt.handled.insert({current->msg.cls, current->msg.id});
  };
  NavPvt pvt;
  NavPosllh posllh;
  NavPosecef posecef;
  NavVelned velned;
  NavVelecef velecef;
  NavStatus status;
  NavSol sol;
  NavSvinfo svinfo;
  NavDop dop;
  NavSat sat;
  NavTimegps timegps;
  NavTimeutc timeutc;
  NavClock clock;
  NavEoe eoe;
  RxmRawx rawx;
  RxmSfrbx sfrbx;
  AckAck ack;
  AckNak nak;
  MonVer ver;
  MonHw hw;
  CfgPrt prt;
  NavSig sig;
  NavSbas sbas;
  NavTimels timels;
  NavTimegal timegal;
  NavTimeglo timeglo;
  NavTimebds timebds;
  MonRf rf;
  MonRxbuf rxbuf;
  MonTxbuf txbuf;
  SecUniqid uniqid;
  for (const Frame& f : frames) {
    current = &f;
    const MsgId m = f.msg;
    if (m == kNavPvt) check("NAV-PVT", reencodes(f, pvt));
    else if (m == kNavPosllh) check("NAV-POSLLH", reencodes(f, posllh));
    else if (m == kNavPosecef) check("NAV-POSECEF", reencodes(f, posecef));
    else if (m == kNavVelned) check("NAV-VELNED", reencodes(f, velned));
    else if (m == kNavVelecef) check("NAV-VELECEF", reencodes(f, velecef));
    else if (m == kNavStatus) check("NAV-STATUS", reencodes(f, status));
    else if (m == kNavSol) check("NAV-SOL", reencodes(f, sol));
    else if (m == kNavSvinfo) check("NAV-SVINFO", reencodes(f, svinfo));
    else if (m == kNavDop) check("NAV-DOP", reencodes(f, dop));
    else if (m == kNavSat) check("NAV-SAT", reencodes(f, sat));
    else if (m == kNavTimegps) check("NAV-TIMEGPS", reencodes(f, timegps));
    else if (m == kNavTimeutc) check("NAV-TIMEUTC", reencodes(f, timeutc));
    else if (m == kNavClock) check("NAV-CLOCK", reencodes(f, clock));
    else if (m == kNavEoe) check("NAV-EOE", reencodes(f, eoe));
    else if (m == kRxmRawx) check("RXM-RAWX", reencodes(f, rawx));
    else if (m == kRxmSfrbx) check("RXM-SFRBX", reencodes(f, sfrbx));
    else if (m == kAckAck) check("ACK-ACK", reencodes(f, ack));
    else if (m == kAckNak) check("ACK-NAK", reencodes(f, nak));
    else if (m == kMonVer) check("MON-VER", reencodes(f, ver));
    else if (m == kMonHw) check("MON-HW", reencodes(f, hw));
    else if (m == kCfgPrt && f.payload.size() == CfgPrt::kPayloadSize)
      check("CFG-PRT", reencodes(f, prt));
    else if (m == kNavSig) check("NAV-SIG", reencodes(f, sig));
    else if (m == kNavSbas) check("NAV-SBAS", reencodes(f, sbas));
    else if (m == kNavTimels) check("NAV-TIMELS", reencodes(f, timels));
    else if (m == kNavTimegal) check("NAV-TIMEGAL", reencodes(f, timegal));
    else if (m == kNavTimeglo) check("NAV-TIMEGLO", reencodes(f, timeglo));
    else if (m == kNavTimebds) check("NAV-TIMEBDS", reencodes(f, timebds));
    else if (m == kMonRf) check("MON-RF", reencodes(f, rf));
    else if (m == kMonRxbuf) check("MON-RXBUF", reencodes(f, rxbuf));
    else if (m == kMonTxbuf) check("MON-TXBUF", reencodes(f, txbuf));
    else if (m == kSecUniqid) check("SEC-UNIQID", reencodes(f, uniqid));
  }
  return rt;
}

std::vector<std::filesystem::path> all_captures() {
  std::vector<std::filesystem::path> files;
  const auto dir = receiver_logs() / "gpsd";
  if (std::filesystem::is_directory(dir))
    for (const auto& e : std::filesystem::directory_iterator(dir))
      if (e.path().extension() == ".log") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  const auto f9t = receiver_logs() / "nav-solutions" / "F9T-L2-5min.ubx";
  if (std::filesystem::is_regular_file(f9t)) files.push_back(f9t);
  return files;
}

TEST(UbxCaptures, EveryFrameParsesAndReencodes) {
  const auto files = all_captures();
  if (files.empty()) GTEST_SKIP() << receiver_logs() << " not found (set NAVEMU_SHARED): skipped";
  int total_frames = 0;
  for (const auto& path : files) {
    SCOPED_TRACE(path.filename().string());
    const Bytes data = read_capture(path);
    const Parsed p = parse_all(data);
    EXPECT_EQ(p.counters.checksum_errors, 0u);
    EXPECT_EQ(p.counters.too_long, 0u);
    EXPECT_EQ(frame_bytes(p) + p.counters.junk_bytes + p.buffered, data.size());
    const RoundTrip rt = round_trip_all(p.frames);
    EXPECT_TRUE(rt.failed.empty());
    std::string summary;
    for (const auto& [name, n] : rt.ok) summary += " " + name + "=" + std::to_string(n);
    for (const auto& [name, n] : rt.failed) summary += " FAILED:" + name + "=" + std::to_string(n);
    // Messages without a struct here, as class-id:count.
    std::map<std::pair<int, int>, int> other = p.count;
    for (const auto& key : rt.handled) other.erase(key);
    std::string others;
    for (const auto& [key, n] : other) {
      char buf[32];
      std::snprintf(buf, sizeof buf, " %02X-%02X=%d", key.first, key.second, n);
      others += buf;
    }
    std::cout << "[ capture  ] " << path.filename().string() << ": " << data.size()
              << " bytes, " << p.counters.frames << " UBX frames, "
              << p.counters.checksum_errors << " checksum errors, " << p.counters.too_long
              << " too long, " << p.counters.junk_bytes << " non-UBX bytes, " << p.buffered
              << " bytes of a frame cut short at the end; re-encoded"
              << summary << "; no struct:" << others << "\n";
    total_frames += static_cast<int>(p.counters.frames);
  }
  EXPECT_GT(total_frames, 0);
}

// The per-satellite messages of every system the captures hold re-encode byte for byte:
// blocks (NAV-SAT, NAV-SIG, RXM-RAWX) and subframes (RXM-SFRBX) counted per gnssId
// (0 GPS, 1 SBAS, 2 Galileo, 3 BeiDou, 5 QZSS, 6 GLONASS) over the frames that re-encode.
TEST(UbxCaptures, EverySystemsSatelliteMessagesReencode) {
  const auto files = all_captures();
  if (files.empty()) GTEST_SKIP() << receiver_logs() << " not found (set NAVEMU_SHARED): skipped";
  std::map<std::string, std::map<int, int>> blocks;  // message -> gnssId -> blocks re-encoded
  int failed = 0;
  for (const auto& path : files) {
    const Parsed p = parse_all(read_capture(path));
    for (const Frame& f : p.frames) {
      const auto count = [&](const char* name, auto& m, auto blocks_of) {
        if (!reencodes(f, m)) {
          ++failed;
          return;
        }
        for (const int gnss_id : blocks_of(m)) ++blocks[name][gnss_id];
      };
      const auto ids = [](const auto& list) {
        std::vector<int> out;
        for (const auto& b : list) out.push_back(b.gnss_id);
        return out;
      };
      NavSat sat;
      NavSig sig;
      RxmRawx rawx;
      RxmSfrbx sfrbx;
      if (f.msg == kNavSat) count("NAV-SAT", sat, [&](const NavSat& m) { return ids(m.svs); });
      if (f.msg == kNavSig) count("NAV-SIG", sig, [&](const NavSig& m) { return ids(m.signals); });
      if (f.msg == kRxmRawx) count("RXM-RAWX", rawx, [&](const RxmRawx& m) { return ids(m.meas); });
      if (f.msg == kRxmSfrbx)
        count("RXM-SFRBX", sfrbx, [](const RxmSfrbx& m) { return std::vector<int>{m.gnss_id}; });
    }
  }
  EXPECT_EQ(failed, 0);
  for (const auto& [name, per_system] : blocks) {
    std::cout << "[ systems  ] " << name << ":";
    for (const auto& [gnss_id, n] : per_system) std::cout << " gnssId " << gnss_id << "=" << n;
    std::cout << "\n";
  }
  for (const int gnss_id : {0, 1, 2, 3, 5, 6}) EXPECT_GT(blocks["NAV-SAT"][gnss_id], 0) << gnss_id;
  for (const int gnss_id : {0, 1, 2, 3, 6}) EXPECT_GT(blocks["NAV-SIG"][gnss_id], 0) << gnss_id;
  for (const int gnss_id : {0, 1, 2, 3}) EXPECT_GT(blocks["RXM-RAWX"][gnss_id], 0) << gnss_id;
  for (const int gnss_id : {0, 2, 3, 6}) EXPECT_GT(blocks["RXM-SFRBX"][gnss_id], 0) << gnss_id;
}

// Expected message counts of each capture (../shared/data/README.md, from a checksum-verified
// scan) and what the decoded fields say.
struct Capture {
  Parsed parsed;
  Bytes data;
};

Capture load(const std::filesystem::path& path) {
  Capture c;
  c.data = read_capture(path);
  c.parsed = parse_all(c.data);
  return c;
}

template <typename T>
std::vector<T> all_of(const Parsed& p) {
  std::vector<T> out;
  for (const Frame& f : p.frames) {
    if (!(f.msg == T::kMsg)) continue;
    T m;
    if (decode(f.payload, m)) out.push_back(m);
  }
  return out;
}

TEST(UbxCaptures, LeaM8fMatchesGpsdDecoding) {
  const auto path = receiver_logs() / "gpsd" / "ublox-lea-m8f.log";
  REQUIRE_CAPTURE(path);
  const Capture c = load(path);
  const Parsed& p = c.parsed;
  EXPECT_EQ(p.of(kNavPvt), 28);
  EXPECT_EQ(p.of(kNavSat), 23);
  EXPECT_EQ(p.of(kNavPosecef), 23);
  EXPECT_EQ(p.of(kNavVelecef), 23);
  EXPECT_EQ(p.of(kNavDop), 23);
  EXPECT_EQ(p.of(kNavTimegps), 23);
  EXPECT_EQ(p.of(kMonVer), 4);
  EXPECT_EQ(p.of(kAckAck), 39);
  EXPECT_EQ(p.of(kAckNak), 4);
  EXPECT_EQ(p.of(kCfgPrt), 1);

  const auto ver = all_of<MonVer>(p);
  ASSERT_FALSE(ver.empty());
  EXPECT_EQ(ver[0].sw_version, "2.20 (81289)");
  EXPECT_EQ(ver[0].hw_version, "00080000");
  EXPECT_EQ(protocol_version_x100(ver[0]), 1600);  // "PROTVER 16.00", with a space
  EXPECT_NE(std::find(ver[0].extensions.begin(), ver[0].extensions.end(), "MOD LEA-M8F-0"),
            ver[0].extensions.end());

  // gpsd's .chk: first TPV 2025-04-11T05:06:25Z, lat -34.9082196, lon 138.5961479, altHAE
  // 60.505 m, ecef (-3927581.26, 3463097.99, -3629556.18) m, pAcc 1.3 m; fixType 5 (time).
  bool seen = false;
  for (const NavPvt& pvt : all_of<NavPvt>(p)) {
    if (pvt.hour != 5 || pvt.min != 6 || pvt.sec != 25) continue;
    seen = true;
    EXPECT_EQ(pvt.year, 2025);
    EXPECT_EQ(pvt.lat_1e7deg, -349082196);
    EXPECT_EQ(pvt.lon_1e7deg, 1385961479);
    EXPECT_EQ(pvt.height_mm, 60505);
    EXPECT_EQ(pvt.fix_type, kFixTimeOnly);
  }
  EXPECT_TRUE(seen);
  const auto ecef = all_of<NavPosecef>(p);
  ASSERT_FALSE(ecef.empty());
  EXPECT_EQ(ecef[0].ecef_x_cm, -392758126);
  EXPECT_EQ(ecef[0].ecef_y_cm, 346309799);
  EXPECT_EQ(ecef[0].ecef_z_cm, -362955618);
  EXPECT_EQ(ecef[0].p_acc_cm, 130u);

  // The CFG-PRT answer is for USB (port 3): UBX+NMEA+RTCM2 in, UBX+NMEA out.
  for (const Frame& f : p.frames) {
    if (!(f.msg == kCfgPrt)) continue;
    CfgPrt prt;
    ASSERT_TRUE(decode(f.payload, prt));
    EXPECT_EQ(prt.port_id, kPortUsb);
    EXPECT_EQ(prt.in_proto_mask, kProtoUbx | kProtoNmea | kProtoRtcm);
    EXPECT_EQ(prt.out_proto_mask, kProtoUbx | kProtoNmea);
  }
}

TEST(UbxCaptures, Ublox8SvinfoSolMonVer) {
  const auto path = receiver_logs() / "gpsd" / "ublox8-uniqid-monhw.log";
  REQUIRE_CAPTURE(path);
  const Parsed p = load(path).parsed;
  EXPECT_EQ(p.of(kNavSvinfo), 7);
  EXPECT_EQ(p.of(kNavSol), 7);
  EXPECT_EQ(p.of(kNavPvt), 7);
  EXPECT_EQ(p.of(kNavSat), 7);
  EXPECT_EQ(p.of(kMonVer), 4);
  const auto ver = all_of<MonVer>(p);
  ASSERT_FALSE(ver.empty());
  EXPECT_EQ(ver[0].sw_version, "ROM CORE 3.01 (107888)");
  EXPECT_EQ(protocol_version_x100(ver[0]), 1800);
  // NAV-SVINFO and NAV-SAT of the same epoch list the same number of satellites.
  const auto svinfo = all_of<NavSvinfo>(p);
  const auto sat = all_of<NavSat>(p);
  ASSERT_FALSE(svinfo.empty());
  for (const NavSvinfo& s : svinfo) {
    EXPECT_EQ(s.global_flags & 0x7, 4);  // chipGen 4: u-blox 8
    for (const NavSat& n : sat) {
      if (n.i_tow_ms == s.i_tow_ms) {
        EXPECT_EQ(n.svs.size(), s.channels.size());
      }
    }
  }
}

TEST(UbxCaptures, NeoM8tRawx) {
  const auto path = receiver_logs() / "gpsd" / "ublox-neo-m8t.log";
  REQUIRE_CAPTURE(path);
  const Parsed p = load(path).parsed;
  EXPECT_EQ(p.of(kRxmRawx), 39);
  EXPECT_EQ(p.of(kNavSol), 39);
  EXPECT_EQ(p.of(kNavSat), 4);
  int gps = 0, sbas = 0;
  for (const RxmRawx& r : all_of<RxmRawx>(p)) {
    EXPECT_NE(r.week, 0);
    EXPECT_EQ(r.version, 1);  // already set by this u-blox 8 firmware
    for (const RxmRawxMeas& m : r.meas) {
      gps += m.gnss_id == 0;
      sbas += m.gnss_id == 1;
      if (m.trk_stat & RxmRawxMeas::kPrValid) {
        // The receiver clock runs about 8 ms early (rcvTow ends in .992): GPS pseudoranges
        // start near 18.2e6 m rather than the 20.2e6 m of a satellite at the zenith.
        EXPECT_GT(m.pr_mes_m, 1.7e7);
        EXPECT_LT(m.pr_mes_m, 4.2e7);
      }
    }
  }
  EXPECT_EQ(gps, 390);
  EXPECT_EQ(sbas, 117);
}

TEST(UbxCaptures, ZedF9pPvtAndSubframes) {
  const auto path = receiver_logs() / "gpsd" / "ublox-zed-f9p-sfrbx.log";
  REQUIRE_CAPTURE(path);
  const Parsed p = load(path).parsed;
  EXPECT_EQ(p.of(kNavPvt), 19);
  EXPECT_EQ(p.of(kRxmSfrbx), 55);
  // gpsd's .chk, first TPV 21:27:57: lat 44.0688649, lon -121.3140956, altHAE 1108.672 m.
  bool seen = false;
  for (const NavPvt& pvt : all_of<NavPvt>(p)) {
    if (pvt.hour != 21 || pvt.min != 27 || pvt.sec != 57) continue;
    seen = true;
    EXPECT_EQ(pvt.lat_1e7deg, 440688649);
    EXPECT_EQ(pvt.lon_1e7deg, -1213140956);
    EXPECT_EQ(pvt.height_mm, 1108672);
    EXPECT_EQ(pvt.h_msl_mm, 1130022);
    EXPECT_EQ(pvt.fix_type, kFix3d);
    EXPECT_TRUE(pvt.flags & NavPvt::kGnssFixOk);
  }
  EXPECT_TRUE(seen);
  // GPS L1 C/A subframes: 10 words, the 30-bit word right-aligned, TLM preamble 0x8B first.
  int gps = 0;
  for (const RxmSfrbx& s : all_of<RxmSfrbx>(p)) {
    if (s.gnss_id != 0) continue;
    ++gps;
    ASSERT_EQ(s.words.size(), 10u);
    EXPECT_EQ(s.words[0] >> 22, 0x8Bu);
  }
  EXPECT_GT(gps, 0);
}

TEST(UbxCaptures, ZedF9tFiveMinutes) {
  const auto path = receiver_logs() / "nav-solutions" / "F9T-L2-5min.ubx";
  REQUIRE_CAPTURE(path);
  const Capture c = load(path);
  const Parsed& p = c.parsed;
  EXPECT_EQ(p.of(kRxmRawx), 299);
  EXPECT_EQ(p.of(kNavPvt), 299);
  EXPECT_EQ(p.of(kNavSat), 299);
  EXPECT_EQ(p.of(kNavClock), 299);
  EXPECT_EQ(p.of(kNavEoe), 299);
  EXPECT_EQ(p.of(kMonRf), 75);
  // The file opens with gpsd's JSON (VERSION, DEVICES, WATCH: it was recorded through gpsd
  // with raw=2); those bytes are the only non-UBX ones.
  EXPECT_EQ(c.data[0], '{');
  EXPECT_EQ(p.counters.junk_bytes, 644u);
  for (const RxmRawx& r : all_of<RxmRawx>(p)) {
    EXPECT_EQ(r.version, 1);  // protocol 27+
    EXPECT_EQ(r.leap_s, 18);
  }
  const auto pvt = all_of<NavPvt>(p);
  ASSERT_FALSE(pvt.empty());
  EXPECT_NEAR(pvt[0].lat_1e7deg * 1e-7, 44.06881, 1e-4);
  EXPECT_NEAR(pvt[0].lon_1e7deg * 1e-7, -121.31403, 1e-4);
  EXPECT_NEAR(pvt[0].height_mm * 1e-3, 1110.3, 1.0);
}

// RXM-RAWX stdev fields (F9 HPG 1.32 interface description): prStdev 0.01 * 2^n m, cpStdev
// 0.004 * n cycles (15 invalid), doStdev 0.002 * 2^n Hz; the nearest index, log scale for 2^n.
TEST(UbxMessages, RawxStdevFieldsQuantiseAsTheInterfaceDescription) {
  EXPECT_EQ(rawx_pr_stdev(0.32), 5);
  EXPECT_EQ(rawx_pr_stdev(0.08), 3);
  EXPECT_EQ(rawx_pr_stdev(0.08 * 1.40), 3);  // below sqrt(2) x 0.08: nearer 0.08 than 0.16
  EXPECT_EQ(rawx_pr_stdev(0.08 * 1.42), 4);
  EXPECT_EQ(rawx_pr_stdev(0.001), 0);
  EXPECT_EQ(rawx_pr_stdev(0.0), 0);
  EXPECT_EQ(rawx_pr_stdev(1e6), 15);
  EXPECT_EQ(rawx_pr_stdev(std::numeric_limits<double>::infinity()), 15);
  EXPECT_EQ(rawx_pr_stdev(std::numeric_limits<double>::quiet_NaN()), 15);
  EXPECT_EQ(rawx_cp_stdev(std::numeric_limits<double>::quiet_NaN()), 15);
  EXPECT_EQ(rawx_do_stdev(0.128), 6);
  EXPECT_EQ(rawx_do_stdev(0.064), 5);
  EXPECT_EQ(rawx_do_stdev(1e3), 15);
  EXPECT_EQ(rawx_cp_stdev(0.004), 1);
  EXPECT_EQ(rawx_cp_stdev(0.0005), 1);  // never 0: no phase is perfect
  EXPECT_EQ(rawx_cp_stdev(0.012), 3);
  EXPECT_EQ(rawx_cp_stdev(0.0139), 3);
  EXPECT_EQ(rawx_cp_stdev(0.0141), 4);
  EXPECT_EQ(rawx_cp_stdev(0.06), 15);
  EXPECT_EQ(rawx_cp_stdev(0.5), 15);
}

TEST(UbxCaptures, M10AndF9tTimingEpochs) {
  for (const char* name : {"ublox-glo.log", "ublox-zed-f9t-ubx_nmea_l5.log"}) {
    const auto path = receiver_logs() / "gpsd" / name;
    REQUIRE_CAPTURE(path);
    SCOPED_TRACE(name);
    const Parsed p = load(path).parsed;
    // Each epoch ends with NAV-EOE carrying the epoch's iTOW, after its NAV-PVT.
    std::uint32_t last_pvt_tow = 0;
    int checked = 0;
    for (const Frame& f : p.frames) {
      if (f.msg == kNavPvt) {
        NavPvt pvt;
        ASSERT_TRUE(decode(f.payload, pvt));
        last_pvt_tow = pvt.i_tow_ms;
      } else if (f.msg == kNavEoe && last_pvt_tow != 0) {
        NavEoe eoe;
        ASSERT_TRUE(decode(f.payload, eoe));
        EXPECT_EQ(eoe.i_tow_ms, last_pvt_tow);
        ++checked;
      }
    }
    EXPECT_GT(checked, 0);
  }
}

// ---- robustness ----------------------------------------------------------------------------

// Every decoder on the given payload (results ignored): must not crash or read out of bounds.
void decode_everything(std::span<const std::uint8_t> b) {
  NavPvt a1;
  NavPosllh a2;
  NavPosecef a3;
  NavVelned a4;
  NavVelecef a5;
  NavStatus a6;
  NavSol a7;
  NavSvinfo a8;
  NavDop a9;
  NavSat a10;
  NavTimegps a11;
  NavTimeutc a12;
  NavClock a13;
  NavEoe a14;
  RxmRawx a15;
  RxmSfrbx a16;
  AckAck a17;
  AckNak a18;
  MonVer a19;
  MonHw a20;
  CfgPrtPoll a21;
  CfgPrt a22;
  CfgMsgPoll a23;
  CfgMsgCurrentPort a24;
  CfgMsg a25;
  CfgRate a26;
  CfgNav5 a27;
  CfgGnss a28;
  CfgCfg a29;
  CfgRst a30;
  CfgValgetRequest a31;
  CfgValgetResponse a32;
  CfgValset a33;
  CfgValdel a34;
  (void)decode(b, a1), (void)decode(b, a2), (void)decode(b, a3), (void)decode(b, a4);
  (void)decode(b, a5), (void)decode(b, a6), (void)decode(b, a7), (void)decode(b, a8);
  (void)decode(b, a9), (void)decode(b, a10), (void)decode(b, a11), (void)decode(b, a12);
  (void)decode(b, a13), (void)decode(b, a14), (void)decode(b, a15), (void)decode(b, a16);
  (void)decode(b, a17), (void)decode(b, a18), (void)decode(b, a19), (void)decode(b, a20);
  (void)decode(b, a21), (void)decode(b, a22), (void)decode(b, a23), (void)decode(b, a24);
  (void)decode(b, a25), (void)decode(b, a26), (void)decode(b, a27), (void)decode(b, a28);
  (void)decode(b, a29), (void)decode(b, a30), (void)decode(b, a31), (void)decode(b, a32);
  (void)decode(b, a33), (void)decode(b, a34);
  (void)protocol_version_x100(a19);
}

TEST(UbxRobustness, DecodersOnRandomPayloads) {
  std::mt19937 rng(99);
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_int_distribution<int> len(0, 700);
  for (int i = 0; i < 3000; ++i) {
    Bytes b(static_cast<std::size_t>(i < 300 ? i : len(rng)));
    for (auto& x : b) x = static_cast<std::uint8_t>(byte(rng));
    decode_everything(b);
  }
  SUCCEED();
}

TEST(UbxRobustness, DecodersOnTruncatedRealFrames) {
  // Every prefix of one frame of each kind in a real capture: no crash, and a decode that
  // succeeds on a prefix only does so where the layout allows it.
  const auto path = receiver_logs() / "gpsd" / "ublox8-uniqid-monhw.log";
  REQUIRE_CAPTURE(path);
  const Parsed p = load(path).parsed;
  std::map<std::pair<int, int>, bool> done;
  for (const Frame& f : p.frames) {
    if (done[{f.msg.cls, f.msg.id}]) continue;
    done[{f.msg.cls, f.msg.id}] = true;
    for (std::size_t k = 0; k < f.payload.size(); ++k) {
      const auto prefix = std::span<const std::uint8_t>(f.payload).first(k);
      decode_everything(prefix);
      NavSat sat;
      NavSvinfo svinfo;
      NavPvt pvt;
      if (f.msg == kNavSat) {
        EXPECT_FALSE(decode(prefix, sat)) << k;
      }
      if (f.msg == kNavSvinfo) {
        EXPECT_FALSE(decode(prefix, svinfo)) << k;
      }
      if (f.msg == kNavPvt) {
        EXPECT_FALSE(decode(prefix, pvt)) << k;
      }
    }
  }
}


// ---- the descriptions, generically ---------------------------------------------------------

// Every described message through its registry hook (decode, then append): payloads shaped by
// the description (fixed part, counted blocks, blocks to the end, optional last groups,
// configuration key/value pairs) with random contents, and some bytes too many. Whatever
// decodes must append the very same frame, but for what the rules of
// protocols/ubx_messages.hpp drop: bytes after an output message's table (a later protocol's
// extension) and characters after a string's NUL (the frame keeps its length, and appending
// it again changes nothing). A payload longer than an exact-length message must not decode,
// unless the extra bytes are its optional last groups.
TEST(UbxDescriptions, EveryDescribedMessageRoundTrips) {
  std::mt19937 rng(20);
  // Bytes 0 and 1 a quarter of the time (version fields, counts), otherwise any.
  const auto byte = [&] {
    const auto r = static_cast<std::uint32_t>(rng());
    return static_cast<std::uint8_t>(r % 4 == 0 ? (r >> 8) % 2 : r >> 16);
  };
  ASSERT_EQ(messages().size(), 110u);
  for (const MessageInfo& m : messages()) {
    SCOPED_TRACE(m.name);
    int decoded = 0;
    for (int trial = 0; trial < 400; ++trial) {
      Bytes p(m.header_size);
      for (std::uint8_t& b : p) b = byte();
      std::size_t extra = 0;
      if (m.block_size > 0) {
        const std::size_t n = rng() % 4;
        if (m.count_offset < m.header_size) {
          p[m.count_offset] = static_cast<std::uint8_t>(n);
          if (m.count_size == 2) p[m.count_offset + 1] = 0;
        }
        for (std::size_t i = 0; i < n * m.block_size; ++i) p.push_back(byte());
      } else if (m.key_values) {
        for (std::size_t i = rng() % 4; i > 0; --i) {
          const auto key = static_cast<std::uint32_t>((1 + rng() % 5) << 28 | (rng() & 0x0FFFFFFF));
          Writer(p).u4(key);
          for (std::size_t k = cfg_value_size(key); k > 0; --k) p.push_back(byte());
        }
      } else {
        // Beyond the fixed part: none, all of the optional groups, or any number of bytes up to
        // two more than them (part of the groups, a byte or two too many).
        const std::size_t form = rng() % 3;
        extra = form == 0 ? 0 : form == 1 ? m.optional_size : rng() % (m.optional_size + 3);
        for (std::size_t i = 0; i < extra; ++i) p.push_back(byte());
      }
      Bytes out;
      if (!m.reencode(p, out)) continue;
      ++decoded;
      const std::size_t kept = m.length == Length::kAtLeast ? p.size() - extra : p.size();
      const Bytes expected = frame_of(m.id, Bytes(p.begin(), p.begin() + static_cast<std::ptrdiff_t>(kept)));
      if (!m.text) {
        EXPECT_EQ(out, expected) << "trial " << trial;
        continue;
      }
      EXPECT_EQ(out.size(), expected.size()) << "trial " << trial;
      Bytes again;
      ASSERT_TRUE(m.reencode(Bytes(out.begin() + 6, out.end() - 2), again));
      EXPECT_EQ(again, out) << "trial " << trial;
    }
    EXPECT_GE(decoded, 20) << "too few payloads decoded to test the message";
  }
}

// The registry names each message as u-blox does and finds it by class/ID and by name.
TEST(UbxDescriptions, RegistryFindsByIdAndName) {
  ASSERT_NE(find_message(kNavPvt), nullptr);
  EXPECT_STREQ(find_message(kNavPvt)->name, "NAV-PVT");
  EXPECT_EQ(find_message(kNavPvt)->header_size, NavPvt::kPayloadSize);
  ASSERT_NE(find_message("RXM-SFRBX"), nullptr);
  EXPECT_EQ(find_message("RXM-SFRBX")->id, kRxmSfrbx);
  EXPECT_EQ(find_message("RXM-SFRBX")->block_size, 4u);
  EXPECT_EQ(find_message("RXM-SFRBX")->count_offset, 4u);  // numWords
  EXPECT_EQ(find_message(kNavTimels)->header_size, NavTimels::kPayloadSize);
  EXPECT_EQ(find_message(MsgId{kClassNav, 0x05}), nullptr);  // NAV-ATT: not described
  // A message with several forms is found by its first: the CFG-PRT poll (0 or 1 byte).
  ASSERT_NE(find_message(kCfgPrt), nullptr);
  EXPECT_EQ(find_message(kCfgPrt)->header_size, 0u);
  EXPECT_EQ(find_message(kCfgPrt)->optional_size, 1u);
  EXPECT_EQ(find_message("MON-PATCH")->count_size, 2u);
  EXPECT_EQ(find_message("NAV-NONE"), nullptr);
}

// The scales of the descriptions give the quantities gpsd reports for the LEA-M8F capture
// (.chk: lat -34.9082196 deg, lon 138.5961479 deg, altHAE 60.505 m at 2025-04-11T05:06:25Z).
TEST(UbxDescriptions, ScalesGiveTheQuantitiesGpsdReports) {
  const auto path = receiver_logs() / "gpsd" / "ublox-lea-m8f.log";
  REQUIRE_CAPTURE(path);
  const Capture c = load(path);
  bool seen = false;
  for (const NavPvt& pvt : all_of<NavPvt>(c.parsed)) {
    if (pvt.hour != 5 || pvt.min != 6 || pvt.sec != 25) continue;
    seen = true;
    std::map<std::string, double> v;
    layout_of<NavPvt>.for_each_value(pvt, [&](const char* name, Wire, double value) { v[name] = value; });
    EXPECT_NEAR(v["lat"], -34.9082196, 1e-9);
    EXPECT_NEAR(v["lon"], 138.5961479, 1e-9);
    EXPECT_NEAR(v["height"], 60.505, 1e-9);
    EXPECT_EQ(v["year"], 2025.0);
    EXPECT_NEAR(v["iTOW"], pvt.i_tow_ms * 1e-3, 1e-12);
  }
  EXPECT_TRUE(seen);
}

}  // namespace
}  // namespace navemu::ubx
