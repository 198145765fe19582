// u-blox NMEA input and PUBX output (protocols/pubx.hpp) against the interface descriptions'
// examples and real receiver output.
//
// Description examples: u-blox 8 / u-blox M8 Receiver description (UBX-13003221), PUBX
// messages: $PUBX,41,1,0007,0003,19200,0*25, $PUBX,40,GLL,1,0,0,0,0,0*5D, the PUBX,00/03/04
// examples below; u-blox ZED-F9P Interface Description (UBX-18010854 R04) 4.2.2 $EIGBQ,RMC*28,
// 4.2.6 $EIGLQ,RMC*3A, 4.2.7 $EIGNQ,RMC*3A, 4.2.9 $EIGPQ,RMC*3A, and the F9 PUBX polls
// $PUBX,00*33 and $PUBX,04*37. Three of them carry a wrong checksum (GLQ, GNQ: the GPQ one
// copied; PUBX,04): the part would drop them, and so does the reader.
//
// Real output (captures quoted by public parser test suites; no PUBX in ../shared):
//  [M8]   u-blox M8 session of 2019-09-14, 06°41'N 101°37'E, PUBX,00/03/04 of one epoch
//         (libecodroidgnss_parse, test_nmea_parse.java);
//  [P2]   Knio/pynmea2 test/test_proprietary.py: PUBX,00, PUBX,03, PUBX,04 (2014);
//  [PG]   semuconsulting/pynmeagps examples/benchmark.py: PUBX,00 and PUBX,03 of 2021-03-06
//         (NMEA 4.11 talker set, with SBAS satellites of unknown position);
//  [U7]   a u-blox 7 PUBX,04 quoted in a PPS/PTP helper script (2024);
//  [HZ]   coverclock/com-diag-hazer PUBX unit test: PUBX,04 with a 21.7 ms clock bias.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "protocols/nmea.hpp"
#include "protocols/pubx.hpp"
#include "protocols/ubx.hpp"
#include "tests/protocols/nmea_test_fields.hpp"

namespace navemu::pubx {
namespace {

using nmea::test_fields::Fields;
using nmea::test_fields::inum;
using nmea::test_fields::must_parse;
using nmea::test_fields::num;
using nmea::test_fields::position_of;
using nmea::test_fields::time_of;

// "$" + body + "*hh\r\n" with the right checksum.
std::string sentence(std::string_view body) {
  return fmt::format("${}*{:02X}\r\n", body, nmea::checksum(body));
}

std::vector<std::uint8_t> bytes_of(std::string_view s) { return {s.begin(), s.end()}; }

std::vector<std::string> read_all(NmeaInputReader& r, std::span<const std::uint8_t> bytes) {
  std::vector<std::string> out;
  r.feed(bytes, [&](std::string_view s) { out.emplace_back(s); });
  return out;
}

// ---- description examples and real host commands --------------------------------------------

const std::vector<std::string> kInputs = {
    "$PUBX,41,1,0007,0003,19200,0*25\r\n",  // M8 description, PUBX,41
    "$PUBX,40,GLL,1,0,0,0,0,0*5D\r\n",      // M8 description, PUBX,40
    "$PUBX,40,GLL,0,0,0,0*5C\r\n",          // the short form hosts send to u-blox 6/7/8
    "$PUBX,00*33\r\n",                      // F9 description, PUBX,00 poll
    "$PUBX,03*30\r\n",
    "$PUBX,04*37\r\n",    // F9 description, PUBX,04 poll
    "$EIGPQ,RMC*3A\r\n",  // ZED-F9P 4.2.9
    "$EIGBQ,RMC*28\r\n",  // ZED-F9P 4.2.2
};

std::string encoded(const Command& c) {
  std::string out;
  encode(c, out);
  return out;
}

// ---- the reader -------------------------------------------------------------------------------

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += x;
  return s;
}

TEST(PubxReader, SentencesSplitAtEveryByte) {
  const std::string stream = joined(kInputs);
  const auto bytes = bytes_of(stream);
  for (std::size_t k = 0; k <= bytes.size(); ++k) {
    NmeaInputReader r;
    std::vector<std::string> got = read_all(r, std::span(bytes).first(k));
    const auto rest = read_all(r, std::span(bytes).subspan(k));
    got.insert(got.end(), rest.begin(), rest.end());
    ASSERT_EQ(got, kInputs) << "split at byte " << k;
    EXPECT_EQ(r.counters().sentences, kInputs.size());
    EXPECT_EQ(r.counters().checksum_errors + r.counters().malformed + r.counters().overlong +
                  r.counters().abandoned,
              0u);
  }
}

TEST(PubxReader, ByteByByteAndTheBufferIsNeverReallocated) {
  NmeaInputReader r;
  std::vector<std::string> got;
  const char* buffer = nullptr;
  for (const std::uint8_t b : bytes_of(joined(kInputs))) {
    if (const auto s = r.feed(b)) {
      if (buffer == nullptr) buffer = s->data();
      EXPECT_EQ(s->data(), buffer);  // one buffer, allocated at construction
      got.emplace_back(*s);
    }
  }
  EXPECT_EQ(got, kInputs);
}

// UBX frames whose payloads hold the bytes that matter to an NMEA reader ('$', '*', CR, LF,
// a sentence without its line end), and random junk, between the sentences: every sentence
// comes out once, in order, and a UBX parser reading the same bytes finds every frame.
TEST(PubxReader, InterleavedWithUbxFramesAndJunk) {
  std::mt19937 rng(20240521);
  std::uniform_int_distribution<int> byte(0, 255), length(0, 40);
  std::vector<std::uint8_t> stream;
  std::size_t frames = 0;
  const std::string tricky = "$PUBX,40,GLL,1,0,0,0,0,0*5D$\r*\n$GP";
  for (int round = 0; round < 20; ++round) {
    for (const std::string& s : kInputs) {
      const int n = length(rng);
      for (int i = 0; i < n; ++i) stream.push_back(static_cast<std::uint8_t>(byte(rng)));
      std::vector<std::uint8_t> payload(tricky.begin(), tricky.end());
      payload.insert(payload.end(), static_cast<std::size_t>(length(rng)), std::uint8_t{0});
      ubx::append_frame(0x06, 0x8A, payload, stream);
      ++frames;
      stream.insert(stream.end(), s.begin(), s.end());
    }
  }
  stream.insert(stream.end(), 5000,
                std::uint8_t{0});  // settles a UBX candidate that junk may have opened
  NmeaInputReader r;
  std::vector<std::string> expected;
  for (int round = 0; round < 20; ++round)
    expected.insert(expected.end(), kInputs.begin(), kInputs.end());
  EXPECT_EQ(read_all(r, stream), expected);
  EXPECT_GT(r.counters().abandoned, 0u);  // the '$' inside the frames and the junk

  ubx::Parser ubx_parser;
  std::size_t ubx_frames = 0;
  ubx_parser.feed(stream, [&](ubx::Parser::Result res) {
    if (res == ubx::Parser::Result::kFrame && ubx_parser.cls() == 0x06) ++ubx_frames;
  });
  EXPECT_EQ(ubx_frames, frames);
}

TEST(PubxReader, BadChecksumIsCountedAndDropped) {
  NmeaInputReader r;
  const std::string s = "$PUBX,00*34\r\n$PUBX,00*33\r\n";
  EXPECT_EQ(read_all(r, bytes_of(s)), std::vector<std::string>{"$PUBX,00*33\r\n"});
  EXPECT_EQ(r.counters().checksum_errors, 1u);
  EXPECT_EQ(r.counters().sentences, 1u);
}

TEST(PubxReader, DescriptionExamplesWithWrongChecksumsAreDropped) {
  NmeaInputReader r;
  // ZED-F9P 4.2.6 and 4.2.7 print the GPQ checksum (the right ones are 26 and 24); the M8
  // description's PUBX,04 example prints 3C (5D is right).
  const std::string s =
      "$EIGLQ,RMC*3A\r\n$EIGNQ,RMC*3A\r\n"
      "$PUBX,04,073731.00,091202,113851.00,1196,15D,1930035,-2660.664,43,*3C\r\n"
      "$EIGLQ,RMC*26\r\n$EIGNQ,RMC*24\r\n";
  EXPECT_EQ(read_all(r, bytes_of(s)),
            (std::vector<std::string>{"$EIGLQ,RMC*26\r\n", "$EIGNQ,RMC*24\r\n"}));
  EXPECT_EQ(r.counters().checksum_errors, 3u);
}

// A body of `n` characters in total with "$", "*hh" and CR LF, and a good checksum.
std::string sentence_of_length(std::size_t n) {
  std::string body = "PUBX,40,GLL,1,0,0,0,0,0";
  body.resize(n - 6, '0');
  return sentence(body);
}

TEST(PubxReader, OverlongLinesAreCountedOnceAndDropped) {
  NmeaInputReader r;  // NMEA 0183 section 5.3: 82 characters from '$' to LF
  ASSERT_EQ(sentence_of_length(82).size(), 82u);
  EXPECT_EQ(read_all(r, bytes_of(sentence_of_length(82))).size(), 1u);
  EXPECT_TRUE(read_all(r, bytes_of(sentence_of_length(83))).empty());
  EXPECT_EQ(r.counters().overlong, 1u);

  // 10 kB of printable junk after a '$', no line end, then a sentence: one overlong line, and
  // the sentence's '$' starts it afresh.
  std::string s = "$" + std::string(10000, 'A') + "$PUBX,00*33\r\n";
  EXPECT_EQ(read_all(r, bytes_of(s)), std::vector<std::string>{"$PUBX,00*33\r\n"});
  EXPECT_EQ(r.counters().overlong, 2u);

  NmeaInputReader wide(200);
  EXPECT_EQ(read_all(wide, bytes_of(sentence_of_length(200))).size(), 1u);
  EXPECT_TRUE(read_all(wide, bytes_of(sentence_of_length(201))).empty());
  EXPECT_EQ(wide.counters().overlong, 1u);
}

TEST(PubxReader, MalformedAndCutLines) {
  NmeaInputReader r;
  // No checksum; a lone CR inside; a cut write followed by the next sentence; a UBX frame
  // cutting a sentence; LF without CR (accepted: NMEA 0183 asks for CR LF, the descriptions do
  // not say what the part does with LF alone).
  const std::string s =
      "$PUBX,00\r\n$PUBX,0\r0*33\r\n$PUBX,0$PUBX,04*37\r\n$PUBX,0\xB5\x62"
      "$PUBX,03*30\n";
  EXPECT_EQ(read_all(r, bytes_of(s)),
            (std::vector<std::string>{"$PUBX,04*37\r\n", "$PUBX,03*30\n"}));
  EXPECT_EQ(r.counters().malformed, 2u);
  EXPECT_EQ(r.counters().abandoned, 2u);
}

TEST(PubxReader, NothingBeforeTheLineEnd) {
  NmeaInputReader r;
  EXPECT_TRUE(read_all(r, bytes_of("$PUBX,00*33\r")).empty());
  EXPECT_EQ(read_all(r, bytes_of("\n")), std::vector<std::string>{"$PUBX,00*33\r\n"});
  r.feed(bytes_of("$PUBX,00*3"), [](std::string_view) {});
  r.reset();
  EXPECT_TRUE(read_all(r, bytes_of("3\r\n")).empty());
}

// ---- parsing the inputs ------------------------------------------------------------------------

template <typename T>
T must_accept(std::string_view s) {
  const Parsed p = parse_input(s);
  EXPECT_EQ(p.reason, Reason::kAccepted)
      << s << ": " << to_string(p.reason) << " field " << p.field << " " << p.field_name;
  if (!p.command || !std::holds_alternative<T>(*p.command)) {
    ADD_FAILURE() << s << " is not the expected command";
    return T{};
  }
  return std::get<T>(*p.command);
}

void expect_rejected(std::string_view s, Reason reason, std::size_t field = 0,
                     std::string_view name = {}) {
  const Parsed p = parse_input(s);
  EXPECT_FALSE(p.command.has_value()) << s;
  EXPECT_EQ(p.reason, reason) << s << ": " << to_string(p.reason);
  EXPECT_EQ(p.field, field) << s;
  EXPECT_EQ(p.field_name, name) << s;
}

TEST(PubxParse, RateDescriptionExample) {
  const SetRate c = must_accept<SetRate>("$PUBX,40,GLL,1,0,0,0,0,0*5D\r\n");
  EXPECT_EQ(c.msg_id.view(), "GLL");
  const std::array<std::optional<std::uint8_t>, kPortCount> rate{1, 0, 0, 0, 0};
  EXPECT_EQ(c.rate, rate);  // DDC 1, UART1, UART2, USB, SPI 0
}

TEST(PubxParse, RateShortFormsLeaveAbsentPortsUnset) {
  const SetRate c = must_accept<SetRate>("$PUBX,40,GLL,0,0,0,0*5C");
  const std::array<std::optional<std::uint8_t>, kPortCount> four{0, 0, 0, 0, std::nullopt};
  EXPECT_EQ(c.rate, four);
  const SetRate e = must_accept<SetRate>(sentence("PUBX,40,RMC,,5,,,"));
  const std::array<std::optional<std::uint8_t>, kPortCount> one{std::nullopt, 5, std::nullopt,
                                                                std::nullopt, std::nullopt};
  EXPECT_EQ(e.rate, one);
  must_accept<SetRate>(sentence("PUBX,40,GGA,0,1,0,0,0,"));  // empty reserved
}

TEST(PubxParse, MalformedRates) {
  expect_rejected(sentence("PUBX,40,gll,1,0,0,0,0,0"), Reason::kBadField, 2, "msgId");
  expect_rejected(sentence("PUBX,40,GLLX,1,0,0,0,0,0"), Reason::kBadField, 2, "msgId");
  expect_rejected(sentence("PUBX,40,,1,0,0,0,0,0"), Reason::kBadField, 2, "msgId");
  expect_rejected(sentence("PUBX,40,GLL,-1,0,0,0,0,0"), Reason::kBadField, 3, "rddc");
  expect_rejected(sentence("PUBX,40,GLL,1,x,0,0,0,0"), Reason::kBadField, 4, "rus1");
  expect_rejected(sentence("PUBX,40,GLL,1,0,256,0,0,0"), Reason::kOutOfRange, 5, "rus2");
  expect_rejected(sentence("PUBX,40,GLL,1,0,0,1.5,0,0"), Reason::kBadField, 6, "rusb");
  expect_rejected(sentence("PUBX,40,GLL,1,0,0,0,0,A"), Reason::kBadField, 8, "reserved");
  expect_rejected(sentence("PUBX,40,GLL"), Reason::kFieldCount, 3);
  expect_rejected(sentence("PUBX,40,GLL,1,0,0,0,0,0,0"), Reason::kFieldCount, 10);
}

TEST(PubxParse, ConfigDescriptionExample) {
  const SetPort c = must_accept<SetPort>("$PUBX,41,1,0007,0003,19200,0*25\r\n");
  EXPECT_EQ(c.port, PortId::kUart1);
  EXPECT_EQ(c.in_proto, ubx::kProtoUbx | ubx::kProtoNmea | ubx::kProtoRtcm);
  EXPECT_EQ(c.out_proto, ubx::kProtoUbx | ubx::kProtoNmea);
  EXPECT_EQ(c.baud_rate, 19200u);
  EXPECT_FALSE(c.autobauding);
}

TEST(PubxParse, ConfigAsHostsSendIt) {
  // Short hex masks ("PUBX,41,1,3,3,9600,0"), lower-case hex, autobauding on, and the UBX-only
  // USB port of issue 21 ("$PUBX,41 with an in/out mask of UBX only stops NMEA").
  const SetPort a = must_accept<SetPort>(sentence("PUBX,41,1,3,3,9600,0"));
  EXPECT_EQ(a.in_proto, 3);
  EXPECT_EQ(a.out_proto, 3);
  const SetPort b = must_accept<SetPort>(sentence("PUBX,41,2,0023,002f,921600,1"));
  EXPECT_EQ(b.port, PortId::kUart2);
  EXPECT_EQ(b.in_proto, ubx::kProtoUbx | ubx::kProtoNmea | ubx::kProtoRtcm3);
  EXPECT_EQ(b.out_proto, 0x2F);
  EXPECT_TRUE(b.autobauding);
  const SetPort usb = must_accept<SetPort>(sentence("PUBX,41,3,0001,0001,9600,0"));
  EXPECT_EQ(usb.port, PortId::kUsb);
  EXPECT_EQ(usb.out_proto, ubx::kProtoUbx);
}

TEST(PubxParse, MalformedConfigs) {
  expect_rejected(sentence("PUBX,41,5,0007,0003,19200,0"), Reason::kOutOfRange, 2, "portId");
  expect_rejected(sentence("PUBX,41,U,0007,0003,19200,0"), Reason::kBadField, 2, "portId");
  expect_rejected(sentence("PUBX,41,1,00G7,0003,19200,0"), Reason::kBadField, 3, "inProto");
  expect_rejected(sentence("PUBX,41,1,0007,00003,19200,0"), Reason::kBadField, 4, "outProto");
  expect_rejected(sentence("PUBX,41,1,0007,,19200,0"), Reason::kBadField, 4, "outProto");
  expect_rejected(sentence("PUBX,41,1,0007,0003,0,0"), Reason::kOutOfRange, 5, "baudrate");
  expect_rejected(sentence("PUBX,41,1,0007,0003,4294967296,0"), Reason::kOutOfRange, 5, "baudrate");
  expect_rejected(sentence("PUBX,41,1,0007,0003,19200.0,0"), Reason::kBadField, 5, "baudrate");
  expect_rejected(sentence("PUBX,41,1,0007,0003,19200,2"), Reason::kBadField, 6, "autobauding");
  expect_rejected(sentence("PUBX,41,1,0007,0003,19200"), Reason::kFieldCount, 6);
  expect_rejected(sentence("PUBX,41,1,0007,0003,19200,0,0"), Reason::kFieldCount, 8);
}

TEST(PubxParse, PubxPolls) {
  EXPECT_EQ(must_accept<PollPubx>("$PUBX,00*33\r\n").msg_id, 0);
  EXPECT_EQ(must_accept<PollPubx>("$PUBX,03*30\r\n").msg_id, 3);
  EXPECT_EQ(must_accept<PollPubx>("$PUBX,04*37\r\n").msg_id, 4);
  // An output sent back is no poll ("polled by sending the PUBX,00 message without any data
  // fields"); PUBX,05/06 are not in the descriptions of these parts.
  expect_rejected(
      "$PUBX,00,035231.00,0641.64673,N,10137.05675,E,19.144,G3,1.2,2.2,0.015,0.00,"
      "0.037,,0.51,0.93,0.58,26,0,0*6D",
      Reason::kFieldCount, 21);
  expect_rejected(sentence("PUBX,05"), Reason::kNotInput, 1, "msgId");
  expect_rejected(sentence("PUBX,4"), Reason::kNotInput, 1, "msgId");
  expect_rejected(sentence("PUBX"), Reason::kFieldCount, 1);
}

TEST(PubxParse, StandardPolls) {
  const PollStandard gpq = must_accept<PollStandard>("$EIGPQ,RMC*3A\r\n");
  EXPECT_EQ(gpq.requester.view(), "EI");
  EXPECT_EQ(gpq.listener.view(), "GP");
  EXPECT_EQ(gpq.msg_id.view(), "RMC");
  EXPECT_EQ(must_accept<PollStandard>("$EIGBQ,RMC*28").listener.view(), "GB");
  for (const std::string listener : {"GN", "GL", "GA", "GQ"}) {
    const auto p = must_accept<PollStandard>(sentence("EI" + listener + "Q,GGA"));
    EXPECT_EQ(p.listener.view(), listener);
    EXPECT_EQ(p.msg_id.view(), "GGA");
  }
  expect_rejected(sentence("EIGXQ,RMC"), Reason::kNotInput);  // no such talker to poll
  expect_rejected(sentence("eiGPQ,RMC"), Reason::kNotInput);
  expect_rejected(sentence("EIGPQ"), Reason::kFieldCount, 1);
  expect_rejected(sentence("EIGPQ,RMC,1"), Reason::kFieldCount, 3);
  expect_rejected(sentence("EIGPQ,rmc"), Reason::kBadField, 1, "msgId");
  expect_rejected(sentence("EIGPQ,RM"), Reason::kBadField, 1, "msgId");
}

TEST(PubxParse, OtherSentencesAndBadFraming) {
  expect_rejected("$GPGGA,185253.00,,,,,0,00,99.99,,,,,,*6E", Reason::kNotInput);
  expect_rejected(sentence("PGRMO,GPGGA,1"), Reason::kNotInput);
  expect_rejected("$PUBX,00*34", Reason::kBadChecksum);
  expect_rejected("$PUBX,00", Reason::kMalformed);
  expect_rejected("PUBX,00*33", Reason::kMalformed);
  EXPECT_EQ(to_string(Reason::kOutOfRange), "field out of range");
}

// Random damage to every input and capture (bytes replaced, inserted, deleted, the sentence
// cut, the checksum recomputed so that the fields are parsed): parse_input() never crashes,
// gives a command exactly when it says kAccepted, and a command it gives encodes to a sentence
// that parses to the same command. The reader takes the same bytes.
TEST(PubxParse, DamagedInputNeverCrashes) {
  std::mt19937 rng(21);
  std::vector<std::string> seeds = kInputs;
  seeds.push_back(
      "$PUBX,00,035231.00,0641.64673,N,10137.05675,E,19.144,G3,1.2,2.2,0.015,0.00,"
      "0.037,,0.51,0.93,0.58,26,0,0*6D\r\n");
  std::uniform_int_distribution<int> byte(0, 255), action(0, 4);
  NmeaInputReader reader;
  std::size_t accepted = 0;
  for (int i = 0; i < 20000; ++i) {
    std::string s = seeds[static_cast<std::size_t>(i) % seeds.size()];
    for (int k = 0; k < 1 + i % 3; ++k) {
      std::uniform_int_distribution<std::size_t> at(0, s.size() - 1);
      const std::size_t pos = at(rng);
      switch (action(rng)) {
        case 0: s[pos] = static_cast<char>(byte(rng)); break;
        case 1: s.insert(pos, 1, static_cast<char>(byte(rng))); break;
        case 2:
          s.insert(pos, 1, ",0123456789ABCDEF-."[static_cast<std::size_t>(byte(rng)) % 19]);
          break;
        case 3:
          if (s.size() > 1) s.erase(pos, 1);
          break;
        default: s.resize(pos + 1);
      }
    }
    std::vector<std::string> variants{s};
    const std::size_t star = s.rfind('*');
    if (s.size() > 1 && s.front() == '$' && star != std::string::npos && star > 1)
      variants.push_back(sentence(std::string_view(s).substr(1, star - 1)));
    for (const std::string& v : variants) {
      const Parsed p = parse_input(v);
      ASSERT_EQ(p.command.has_value(), p.reason == Reason::kAccepted) << v;
      reader.feed(bytes_of(v), [](std::string_view) {});
      if (!p.command) continue;
      ++accepted;
      const Parsed again = parse_input(encoded(*p.command));
      ASSERT_TRUE(again.command) << v;
      EXPECT_EQ(*again.command, *p.command) << v;
    }
  }
  EXPECT_GT(accepted, 100u);  // the damage leaves some commands valid, and they round-trip
}

// ---- input commands encoded: round trips -------------------------------------------------------

TEST(PubxCommands, DescriptionExamplesRoundTrip) {
  for (const std::string& s : kInputs) {
    const Parsed p = parse_input(s);
    ASSERT_TRUE(p.command) << s;
    EXPECT_EQ(encoded(*p.command), s);
  }
}

TEST(PubxCommands, RandomCommandsRoundTrip) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> u8(0, 255), letter('A', 'Z'), coin(0, 1), port(0, 4);
  const auto id3 = [&] {
    return Formatter::of(std::string{static_cast<char>(letter(rng)), static_cast<char>(letter(rng)),
                                     static_cast<char>(letter(rng))});
  };
  for (int i = 0; i < 2000; ++i) {
    Command c;
    switch (i % 4) {
      case 0: {
        SetRate r;
        r.msg_id = id3();
        for (auto& x : r.rate)
          if (coin(rng) != 0) x = static_cast<std::uint8_t>(u8(rng));
        if (!r.rate[0]) r.rate[0] = 1;  // at least one rate field is sent
        c = r;
        break;
      }
      case 1:
        c = SetPort{static_cast<PortId>(port(rng)), static_cast<std::uint16_t>(u8(rng) * 257),
                    static_cast<std::uint16_t>(u8(rng)),
                    static_cast<std::uint32_t>(u8(rng)) * 16777216u + 1u, coin(rng) != 0};
        break;
      case 2:
        c = PollPubx{
            static_cast<std::uint8_t>(std::array{0, 3, 4}[static_cast<std::size_t>(i % 3)])};
        break;
      default:
        c = PollStandard{Talker::of("EI"),
                         Talker::of(std::array{"GP", "GN", "GL", "GB", "GA",
                                               "GQ"}[static_cast<std::size_t>(i % 6)]),
                         id3()};
    }
    const std::string s = encoded(c);
    const Parsed p = parse_input(s);
    ASSERT_TRUE(p.command) << s << ": " << to_string(p.reason) << " " << p.field_name;
    EXPECT_EQ(*p.command, c) << s;
  }
}

// ---- PUBX outputs against real receivers -------------------------------------------------------

std::optional<NavStatus> nav_status_of(const std::string& s) {
  const std::array<std::pair<std::string_view, NavStatus>, 8> codes{{
      {"NF", NavStatus::kNoFix},
      {"DR", NavStatus::kDeadReckoning},
      {"G2", NavStatus::kStandalone2D},
      {"G3", NavStatus::kStandalone3D},
      {"D2", NavStatus::kDifferential2D},
      {"D3", NavStatus::kDifferential3D},
      {"RK", NavStatus::kGnssDeadReckoning},
      {"TT", NavStatus::kTimeOnly},
  }};
  for (const auto& [code, status] : codes)
    if (code == s) return status;
  return std::nullopt;
}

PositionFields position_fields_of(const Fields& f) {
  PositionFields p;
  p.utc = time_of(f[2]);
  p.position = position_of(f, 3);
  p.height_user_datum_m = num(f[7]);
  p.nav_status = nav_status_of(f[8]).value_or(NavStatus::kNoFix);
  p.h_acc_m = num(f[9]);
  p.v_acc_m = num(f[10]);
  if (const auto kmh = num(f[11])) p.speed_mps = *kmh / 3.6;
  p.course_deg = num(f[12]);
  p.velocity_down_mps = num(f[13]);
  p.diff_age_s = num(f[14]);
  p.hdop = num(f[15]);
  p.vdop = num(f[16]);
  p.tdop = num(f[17]);
  p.num_svs = std::stoi(f[18]);
  p.dead_reckoning_used = f[20] == "1";
  return p;
}

std::vector<SvStatus> satellites_of(const Fields& f) {
  std::vector<SvStatus> sats;
  for (std::size_t i = 3; i + 5 < f.size(); i += 6) {
    SvStatus s;
    s.sv_id = std::stoi(f[i]);
    s.use = f[i + 1] == "U"   ? SvUse::kUsed
            : f[i + 1] == "e" ? SvUse::kEphemerisNotUsed
                              : SvUse::kNotUsed;
    s.azimuth_deg = inum(f[i + 2]);
    s.elevation_deg = inum(f[i + 3]);
    s.cno_dbhz = inum(f[i + 4]);
    s.carrier_lock_s = std::stod(f[i + 5]);
    sats.push_back(s);
  }
  EXPECT_EQ(sats.size(), static_cast<std::size_t>(std::stoi(f[2])));
  return sats;
}

TimeFields time_fields_of(const Fields& f) {
  TimeFields t;
  t.utc = time_of(f[2], f[3]);
  t.utc_tow_s = num(f[4]);
  t.utc_week = inum(f[5]);
  std::string leap = f[6];
  t.leap_seconds_default = !leap.empty() && leap.back() == 'D';
  if (t.leap_seconds_default) leap.pop_back();
  t.leap_seconds = inum(leap);
  if (const auto ns = num(f[7])) t.clock_bias_s = *ns * 1e-9;
  if (const auto ns = num(f[8])) t.clock_drift_s_per_s = *ns * 1e-9;
  if (const auto ns = num(f[9])) t.time_pulse_granularity_s = *ns * 1e-9;
  return t;
}

std::string reencoded(const std::string& s) {
  const Fields f = must_parse(s);
  std::string out;
  if (f.size() < 2 || f[0] != "PUBX") return out;
  if (f[1] == "00") encode(position_fields_of(f), nmea::Format::ublox(), out);
  if (f[1] == "03") {
    const auto sats = satellites_of(f);
    encode(SvStatusFields{sats}, out);
  }
  if (f[1] == "04") encode(time_fields_of(f), nmea::Format::ublox(), out);
  return out;
}

const std::vector<std::string> kCaptures = {
    // [M8]
    "$PUBX,00,035231.00,0641.64673,N,10137.05675,E,19.144,G3,1.2,2.2,0.015,0.00,0.037,,0.51,"
    "0.93,0.58,26,0,0*6D",
    "$PUBX,03,32,2,U,352,30,41,064,5,U,295,67,38,064,6,U,039,18,28,064,9,e,049,03,,000,12,U,295,"
    "44,46,064,13,U,171,32,31,061,15,U,204,12,32,064,17,U,106,34,31,007,19,U,089,43,27,003,24,-,"
    "235,06,,000,25,-,315,08,,000,28,e,154,06,,000,30,-,123,-2,,000,211,e,165,14,18,000,214,U,"
    "180,53,30,020,219,-,208,07,,000,221,-,307,05,,000,222,U,354,29,41,064,229,U,068,52,24,000,"
    "234,U,280,29,43,064,236,e,093,00,,000,241,U,214,40,28,026,243,U,051,26,30,064,159,-,099,45,"
    ",000,160,-,253,68,,000,161,-,122,77,,000,162,-,094,23,,000,163,-,264,40,,000,33,e,132,54,10,"
    "000,34,U,177,42,30,020,35,U,020,28,30,064,36,e,169,43,,000*38",
    "$PUBX,04,035231.00,140919,532351.00,2070,18,541289,165.421,08*1A",
    // [P2]
    "$PUBX,00,074440.00,4703.74203,N,00736.82976,E,576.991,D3,2.0,2.0,0.091,0.00,-0.032,,0.76,"
    "1.05,0.65,14,0,0*70",
    "$PUBX,03,20,3,e,281,72,36,062,5,e,034,10,23,000,8,U,328,11,44,064,9,-,323,-2,,000,13,-,341,"
    "01,,000,16,U,307,45,49,064,18,e,144,18,,000,21,U,150,74,35,037,25,e,134,06,,000,27,U,271,20,"
    "52,064,29,U,074,36,36,063,31,U,209,26,37,040,120,e,210,31,,000,126,-,157,33,,000,66,U,036,"
    "19,34,015,67,e,090,20,22,000,68,-,136,00,,000,73,e,273,60,47,064,74,U,330,24,44,064,80,U,"
    "193,36,36,023*33",
    "$PUBX,04,073824.00,131014,113903.99,1814,16,495176,342.504,21*18",
    // [PG]
    "$PUBX,00,103607.00,5327.03942,N,00214.42462,W,104.461,G3,29,31,0.085,39.63,-0.007,,5.88,"
    "7.62,8.09,6,0,0*69",
    "$PUBX,03,23,1,-,014,06,08,000,12,U,207,43,28,009,14,-,049,06,,000,15,-,171,44,23,000,17,-,"
    "064,32,16,000,19,-,094,33,,000,20,U,251,20,31,038,21,-,354,04,,000,23,U,251,27,31,064,24,U,"
    "268,89,26,000,25,-,223,05,,000,48,-,,,15,000,52,-,,,28,013,65,-,176,07,,000,66,U,223,57,35,"
    "064,67,-,315,42,23,000,68,-,341,00,29,000,75,-,057,37,,000,76,U,303,78,18,000,77,-,253,27,"
    "21,000,84,-,018,19,,000,85,-,078,22,,000,86,-,121,01,,000*02",
    // [U7]
    "$PUBX,04,202604.00,150824,419164.00,2327,18,-672045,-11949.632,21*11",
    // [HZ]
    "$PUBX,04,180729.00,200821,497248.99,2171,18,-21669119,376.950,21*3E",
};

TEST(PubxEncode, RealReceiverOutputByteForByte) {
  for (const std::string& s : kCaptures) EXPECT_EQ(reencoded(s), s + "\r\n");
}

// The descriptions' examples, field by field: they come from older firmware than the M8
// captures (six decimals of the minutes, two-digit satellite numbers, a trailing empty field
// in PUBX,04), so only the values must agree.
void expect_same_values(const std::string& ours, std::string_view example_body) {
  const Fields a = must_parse(ours);
  Fields b;
  for (std::size_t start = 0;;) {
    const std::size_t comma = example_body.find(',', start);
    b.emplace_back(example_body.substr(start, comma - start));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  while (!b.empty() && b.back().empty()) b.pop_back();  // PUBX,04's trailing empty field
  const auto is_number = [](const std::string& x) {
    return x.find_first_of("0123456789") != std::string::npos &&
           x.find_first_not_of("0123456789.-") == std::string::npos;
  };
  ASSERT_EQ(a.size(), b.size()) << ours;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (is_number(a[i]) && is_number(b[i])) {
      EXPECT_NEAR(std::stod(a[i]), std::stod(b[i]), 5e-6) << "field " << i << " of " << ours;
    } else {
      EXPECT_EQ(a[i], b[i]) << "field " << i << " of " << ours;
    }
  }
}

TEST(PubxEncode, DescriptionExamples) {
  // u-blox 8 description (the F9 one prints the same sentence with checksum 5B, wrong).
  const std::string pos =
      "$PUBX,00,081350.00,4717.113210,N,00833.915187,E,546.589,G3,2.1,2.0,0.007,77.52,0.007,,"
      "0.92,1.19,0.77,9,0,0*5F";
  ASSERT_EQ(nmea::check(pos).status, nmea::Checked::kOk);
  expect_same_values(reencoded(pos), nmea::check(pos).body);

  const std::string sv =
      "$PUBX,03,11,23,-,,,45,010,29,-,,,46,013,07,-,,,42,015,08,U,067,31,42,025,10,U,195,33,46,"
      "026,18,U,326,08,39,026,17,-,,,32,015,26,U,306,66,48,025,27,U,073,10,36,026,28,U,089,61,46,"
      "024,15,-,,,39,014*0D";
  ASSERT_EQ(nmea::check(sv).status, nmea::Checked::kOk);
  expect_same_values(reencoded(sv), nmea::check(sv).body);

  // Its checksum is wrong (see the reader test): the fields are taken as printed.
  const std::string tim = "$PUBX,04,073731.00,091202,113851.00,1196,15D,1930035,-2660.664,43,*3C";
  const std::string_view tim_body = nmea::check(tim).body;
  ASSERT_EQ(nmea::check(tim).status, nmea::Checked::kBadChecksum);
  const std::string fixed = sentence(tim_body);
  expect_same_values(reencoded(fixed), tim_body);
  EXPECT_NE(reencoded(fixed).find(",15D,"), std::string::npos);
}

TEST(PubxEncode, NoFixAsTheM8SendsIt) {
  // A u-blox no-fix PUBX,00 (quoted in a public u-blox NMEA parser): zeros, NF, the accuracy
  // estimates of a receiver without a fix and DOPs of 99.99; the device fills them so.
  const std::string s =
      "$PUBX,00,000717.00,0000.00000,N,00000.00000,E,0.000,NF,5303316,3750010,0.000,0.00,0.000,,"
      "99.99,99.99,99.99,0,0,0*2C";
  EXPECT_EQ(reencoded(s), s + "\r\n");
}

TEST(PubxEncode, UnsetAndNonFiniteFieldsAreEmpty) {
  std::string out;
  PositionFields p;
  p.h_acc_m = std::numeric_limits<double>::quiet_NaN();
  p.speed_mps = std::numeric_limits<double>::infinity();
  encode(p, nmea::Format::ublox(), out);
  EXPECT_EQ(out, sentence("PUBX,00,000000.00,,,,,,NF,,,,,,,,,,0,0,0"));
  EXPECT_EQ(must_parse(out).size(), 21u);  // the 21 fields of the description's layout

  out.clear();
  encode(TimeFields{}, nmea::Format::ublox(), out);
  EXPECT_EQ(out, sentence("PUBX,04,000000.00,010100,,,,,,"));

  out.clear();
  encode(SvStatusFields{}, out);
  EXPECT_EQ(out, sentence("PUBX,03,0"));
}

TEST(PubxEncode, RoundingClampingAndSigns) {
  std::string out;
  PositionFields p;
  p.utc = {2019, 12, 31, 23, 59, 59.996};
  p.position = nmea::LatLon{-33.9999999999, -151.0};
  p.velocity_down_mps = -0.0004;  // rounds to zero: no "-0.000"
  p.course_deg = 359.999;         // rounds to 360: sent as 0
  p.speed_mps = 1.0;              // 3.600 km/h
  p.h_acc_m = 0.0143;             // two significant digits
  p.v_acc_m = 1e12;               // clamped
  p.hdop = 250.0;                 // clamped
  p.num_svs = 300;
  p.dead_reckoning_used = true;
  encode(p, nmea::Format::ublox(), out);
  EXPECT_EQ(out, sentence("PUBX,00,000000.00,3400.00000,S,15100.00000,W,,NF,0.014,9999999,3.600,"
                          "0.00,0.000,,99.99,,,255,0,1"));

  out.clear();
  TimeFields t;
  t.utc = {2019, 12, 31, 23, 59, 59.996};  // carries into the next day and year
  t.leap_seconds = 18;
  t.leap_seconds_default = true;
  t.clock_bias_s = -0.0216691186;
  t.clock_drift_s_per_s = -0.0000000000001;  // -0.0001 ns/s: no "-0.000"
  t.time_pulse_granularity_s = 5e-9;
  encode(t, nmea::Format::ublox(), out);
  EXPECT_EQ(out, sentence("PUBX,04,000000.00,010120,,,18D,-21669119,0.000,05"));

  out.clear();
  const std::array<SvStatus, 3> sats{{
      {7, SvUse::kUsed, 360, -2, 45, 12.9},
      {120, SvUse::kEphemerisNotUsed, -5, 95, 150, 1e6},
      {1000, SvUse::kNotUsed, std::nullopt, std::nullopt, std::nullopt,
       std::numeric_limits<double>::quiet_NaN()},
  }};
  encode(SvStatusFields{sats}, out);
  EXPECT_EQ(out, sentence("PUBX,03,3,7,U,000,-2,45,012,120,e,355,90,99,064,999,-,,,,000"));
}

// The longest PUBX,00 and PUBX,04 (every field at the end of its range, three decimals of
// seconds) come out whole: all fields, a checksum that matches.
TEST(PubxEncode, LongestSentencesAreWhole) {
  std::string out;
  PositionFields p;
  p.utc = {2019, 12, 31, 23, 59, 59.123};
  p.position = nmea::LatLon{-89.9999999, -179.9999999};
  p.height_user_datum_m = -99999.999;
  p.nav_status = NavStatus::kGnssDeadReckoning;
  p.h_acc_m = p.v_acc_m = 9999999.0;
  p.speed_mps = 99999.999 / 3.6;
  p.course_deg = 359.99;
  p.velocity_down_mps = -9999.999;
  p.diff_age_s = 999.9;
  p.hdop = p.vdop = p.tdop = 99.99;
  p.num_svs = 255;
  p.dead_reckoning_used = true;
  nmea::Format fmt = nmea::Format::ublox();
  fmt.time_decimals = 3;
  encode(p, fmt, out);
  const Fields f = must_parse(out);
  ASSERT_EQ(f.size(), 21u) << out;
  EXPECT_EQ(f[7], "-99999.999");
  EXPECT_EQ(f[20], "1");

  out.clear();
  TimeFields t;
  t.utc = p.utc;
  t.utc_tow_s = 604799.99;
  t.utc_week = 99999;
  t.leap_seconds = -99;
  t.leap_seconds_default = true;
  t.clock_bias_s = -999.999;
  t.clock_drift_s_per_s = -1e-3;
  t.time_pulse_granularity_s = 999e-9;
  encode(t, fmt, out);
  const Fields g = must_parse(out);
  ASSERT_EQ(g.size(), 10u) << out;
  EXPECT_EQ(g[7], "-999999000000");
  EXPECT_EQ(g[9], "999");
}

}  // namespace
}  // namespace navemu::pubx
