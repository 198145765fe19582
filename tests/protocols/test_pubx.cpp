// u-blox NMEA input (protocols/pubx.hpp) against the interface descriptions' examples.
//
// Description examples: u-blox 8 / u-blox M8 Receiver description (UBX-13003221), PUBX
// messages: $PUBX,41,1,0007,0003,19200,0*25, $PUBX,40,GLL,1,0,0,0,0,0*5D, the PUBX,00/03/04
// examples below; u-blox ZED-F9P Interface Description (UBX-18010854 R04) 4.2.2 $EIGBQ,RMC*28,
// 4.2.6 $EIGLQ,RMC*3A, 4.2.7 $EIGNQ,RMC*3A, 4.2.9 $EIGPQ,RMC*3A, and the F9 PUBX polls
// $PUBX,00*33 and $PUBX,04*37. Three of them carry a wrong checksum (GLQ, GNQ: the GPQ one
// copied; PUBX,04): the part would drop them, and so does the reader.

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
    "$PUBX,04*37\r\n",                      // F9 description, PUBX,04 poll
    "$EIGPQ,RMC*3A\r\n",                    // ZED-F9P 4.2.9
    "$EIGBQ,RMC*28\r\n",                    // ZED-F9P 4.2.2
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
  stream.insert(stream.end(), 5000, std::uint8_t{0});  // settles a UBX candidate that junk may have opened
  NmeaInputReader r;
  std::vector<std::string> expected;
  for (int round = 0; round < 20; ++round) expected.insert(expected.end(), kInputs.begin(), kInputs.end());
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
  const std::string s = "$PUBX,00\r\n$PUBX,0\r0*33\r\n$PUBX,0$PUBX,04*37\r\n$PUBX,0\xB5\x62"
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
  EXPECT_EQ(p.reason, Reason::kAccepted) << s << ": " << to_string(p.reason) << " field "
                                         << p.field << " " << p.field_name;
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
  EXPECT_EQ(c.in_proto, kProtoUbx | kProtoNmea | kProtoRtcm2);
  EXPECT_EQ(c.out_proto, kProtoUbx | kProtoNmea);
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
  EXPECT_EQ(b.in_proto, kProtoUbx | kProtoNmea | kProtoRtcm3);
  EXPECT_EQ(b.out_proto, 0x2F);
  EXPECT_TRUE(b.autobauding);
  const SetPort usb = must_accept<SetPort>(sentence("PUBX,41,3,0001,0001,9600,0"));
  EXPECT_EQ(usb.port, PortId::kUsb);
  EXPECT_EQ(usb.out_proto, kProtoUbx);
}

TEST(PubxParse, MalformedConfigs) {
  expect_rejected(sentence("PUBX,41,5,0007,0003,19200,0"), Reason::kOutOfRange, 2, "portId");
  expect_rejected(sentence("PUBX,41,U,0007,0003,19200,0"), Reason::kBadField, 2, "portId");
  expect_rejected(sentence("PUBX,41,1,00G7,0003,19200,0"), Reason::kBadField, 3, "inProto");
  expect_rejected(sentence("PUBX,41,1,0007,00003,19200,0"), Reason::kBadField, 4, "outProto");
  expect_rejected(sentence("PUBX,41,1,0007,,19200,0"), Reason::kBadField, 4, "outProto");
  expect_rejected(sentence("PUBX,41,1,0007,0003,0,0"), Reason::kOutOfRange, 5, "baudrate");
  expect_rejected(sentence("PUBX,41,1,0007,0003,4294967296,0"), Reason::kOutOfRange, 5,
                  "baudrate");
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
  expect_rejected("$PUBX,00,035231.00,0641.64673,N,10137.05675,E,19.144,G3,1.2,2.2,0.015,0.00,"
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
  seeds.push_back("$PUBX,00,035231.00,0641.64673,N,10137.05675,E,19.144,G3,1.2,2.2,0.015,0.00,"
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
        case 2: s.insert(pos, 1, ",0123456789ABCDEF-."[static_cast<std::size_t>(byte(rng)) % 19]); break;
        case 3: if (s.size() > 1) s.erase(pos, 1); break;
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
        c = PollPubx{static_cast<std::uint8_t>(std::array{0, 3, 4}[static_cast<std::size_t>(i % 3)])};
        break;
      default:
        c = PollStandard{Talker::of("EI"),
                         Talker::of(std::array{"GP", "GN", "GL", "GB", "GA", "GQ"}[static_cast<std::size_t>(i % 6)]),
                         id3()};
    }
    const std::string s = encoded(c);
    const Parsed p = parse_input(s);
    ASSERT_TRUE(p.command) << s << ": " << to_string(p.reason) << " " << p.field_name;
    EXPECT_EQ(*p.command, c) << s;
  }
}

}  // namespace
}  // namespace navemu::pubx
