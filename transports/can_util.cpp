// CAN payload lengths and their DLC codes. ISO 11898-1:2015, DLC coding (table 5): DLC 0..8
// mean 0..8 bytes; in CAN FD frames DLC 9..15 mean 12, 16, 20, 24, 32, 48, 64 bytes (in
// classic frames they mean 8). The same table as Linux include/linux/can/length.h.

#include "transports/can_util.hpp"

#include <array>

#include "transports/can_port.hpp"

namespace navemu::transport {
namespace {

constexpr std::array<std::uint8_t, 16> kLengthOfDlc = {0, 1,  2,  3,  4,  5,  6,  7,
                                                       8, 12, 16, 20, 24, 32, 48, 64};

}  // namespace

bool valid_can_length(std::size_t len, bool fd) {
  if (len <= 8) return true;
  return fd && can_length_from_dlc(can_dlc_from_length(len)) == len;
}

// The smallest DLC whose payload holds `len` bytes (a CAN FD frame is padded up to it);
// lengths over 64 give 15.
std::uint8_t can_dlc_from_length(std::size_t len) {
  for (std::uint8_t dlc = 0; dlc < kLengthOfDlc.size(); ++dlc)
    if (kLengthOfDlc[dlc] >= len) return dlc;
  return 15;
}

// The CAN FD payload length of a DLC; only the low 4 bits of `dlc` count.
std::size_t can_length_from_dlc(std::uint8_t dlc) { return kLengthOfDlc[dlc & 0x0Fu]; }

bool valid_can_frame(const CanFrameView& frame) {
  if (frame.error) return !frame.extended && !frame.fd && frame.id <= 0x1FFFFFFFu && frame.data.size() == 8;
  const std::uint32_t max_id = frame.extended ? 0x1FFFFFFFu : 0x7FFu;
  return frame.id <= max_id && valid_can_length(frame.data.size(), frame.fd);
}

}  // namespace navemu::transport
