// The truth datagram decoder (protocols/truth_datagram.hpp, docs/truth-protocol.md), binary and
// JSON, as the UDP truth source receives datagrams from the network. Every datagram it accepts
// must survive the round trip: encoding the decoded message in binary and decoding it again
// gives the same message, and so does JSON when the values are finite (the state the emulator
// would use). The state then goes into a truth buffer behind a steady 10 Hz stream, three times
// 0.1 s apart (emulator/truth_buffer.hpp, "Re-synchronisation"): the stream's time never runs
// backwards, a refused sample changes nothing, three consistent outliers re-synchronise the
// stream one step after its newest sample, and every sample is counted once.

#include <cstdint>
#include <cstring>

#include "emulator/truth_buffer.hpp"
#include "emulator/truth_source.hpp"
#include "protocols/truth_datagram.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace td = navemu::truth_datagram;

namespace {

using navemu::GpsTime;
using navemu::TruthVerdict;

void check_resync(navemu::ImuTruth s) {
  navemu::TruthBuffer b(navemu::TruthStreamLimits{1.0, 10.0, 5.0, 3});
  const GpsTime base{1'400'000'000'000'000'000};
  navemu::ImuTruth steady = s;
  for (int k = 0; k < 10; ++k) {
    steady.t = GpsTime{base.ns + k * 100'000'000};
    if (b.push(steady) != TruthVerdict::kAccepted && k == 0) return;  // its values are refused
  }
  const GpsTime newest0 = *b.newest_time();
  if (s.t.ns > INT64_MAX - 1'000'000'000) return;  // no room for the two after it
  TruthVerdict verdicts[3]{};
  for (int k = 0; k < 3; ++k) {
    const GpsTime before = *b.newest_time();
    navemu::ImuTruth x = s;
    x.t = GpsTime{s.t.ns + k * 100'000'000};
    const TruthVerdict v = b.push(x);
    verdicts[k] = v;
    const GpsTime after = *b.newest_time();
    if (after < before) navemu::fuzz::fail("the truth stream's time ran backwards");
    if (v == TruthVerdict::kAccepted && after != x.t) navemu::fuzz::fail("an accepted sample is not the newest");
    if (v != TruthVerdict::kAccepted && v != TruthVerdict::kResync && after != before)
      navemu::fuzz::fail("a refused sample moved the stream");
  }
  const auto outlier = [](TruthVerdict v) { return v == TruthVerdict::kFuture || v == TruthVerdict::kBackwards; };
  if (outlier(verdicts[0]) && outlier(verdicts[1]) && outlier(verdicts[2]))
    navemu::fuzz::fail("three consistent outliers did not re-synchronise");
  if (verdicts[2] == TruthVerdict::kResync &&
      (b.counters().resync != 1 || *b.newest_time() != GpsTime{newest0.ns + 100'000'000}))
    navemu::fuzz::fail("the stream was not re-synchronised one step after its newest sample");
  const navemu::TruthCounters& c = b.counters();
  if (c.accepted + c.rejected() != 13) navemu::fuzz::fail("a sample was not counted exactly once");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  td::Message m;
  if (td::decode(navemu::fuzz::bytes_of(data, size), m) != td::DecodeResult::kOk) return 0;

  const auto binary = td::encode_binary(m);
  td::Message again;
  if (td::decode(binary, again) != td::DecodeResult::kOk)
    navemu::fuzz::fail("an accepted message does not decode after binary encoding");
  if (td::encode_binary(again) != binary) navemu::fuzz::fail("the binary round trip changed the message");

  if (!navemu::truth_from_message(m, navemu::GpsTime{0})) return 0;  // not finite: rejected
  const std::string json = td::encode_json(m);
  td::Message from_json;
  if (td::decode_json(json, from_json) != td::DecodeResult::kOk)
    navemu::fuzz::fail("an accepted message does not decode after JSON encoding");
  if (td::encode_binary(from_json) != binary) navemu::fuzz::fail("the JSON round trip changed the message");
  check_resync(*navemu::truth_from_message(m, navemu::GpsTime{0}));
  return 0;
}
