// The truth datagram decoder (protocols/truth_datagram.hpp, docs/truth-protocol.md), binary and
// JSON, as the UDP truth source receives datagrams from the network. Every datagram it accepts
// must survive the round trip: encoding the decoded message in binary and decoding it again
// gives the same message, and so does JSON when the values are finite (the state the emulator
// would use).

#include <cstdint>
#include <cstring>

#include "emulator/truth_source.hpp"
#include "protocols/truth_datagram.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace td = navemu::truth_datagram;

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
  return 0;
}
