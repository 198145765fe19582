// The slcan adapter's command side (transports/can_port.hpp, SlcanPort): the bytes a client
// sends arrive through a byte port in pieces of 1 to 64 bytes (byte 0 sets the piece size and
// whether the channel starts open); each service() reads its piece whole and answers the
// complete commands, and a frame goes out between pieces. Every command is answered with at most
// 7 bytes (CR, BEL or a version line), so the port never carries more than 7 bytes per input
// byte besides the frames.

#include <algorithm>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "tests/fuzz/fuzz_support.hpp"
#include "transports/can_port.hpp"

using navemu::fuzz::MemoryPort;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  auto port = std::make_unique<MemoryPort>();
  MemoryPort& memory = *port;
  auto slcan = navemu::transport::open_slcan(std::move(port), {.auto_open = (data[0] & 0x80) != 0});
  const std::size_t piece = 1 + (data[0] & 0x3F);
  const std::uint8_t payload[8] = {1, 2, 3, 4, 5, 6, 7, 8};
  const navemu::transport::CanFrameView frame{.id = 0x123, .data = payload};
  auto input = navemu::fuzz::bytes_of(data + 1, size - 1);
  std::size_t pieces = 0;
  while (!input.empty()) {
    const std::size_t n = std::min(piece, input.size());
    memory.pending = input.first(n);
    input = input.subspan(n);
    slcan->service();
    if (!memory.pending.empty()) navemu::fuzz::fail("service() left input unread");
    (void)slcan->write(frame, 0);
    ++pieces;
  }
  // Each answer is at most 7 bytes ("V1013\r") per command; a command takes at least 1 byte.
  const std::size_t frame_lines = pieces * 22;  // "t1238" + 16 hex digits + CR
  if (memory.written.size() > 7 * (size + pieces) + frame_lines) navemu::fuzz::fail("more answers than commands");
  return 0;
}
