#pragma once
// Helpers shared by the frame ports (not part of the public transport interface).

#include "transports/can_port.hpp"

namespace navemu::transport {

// Whether a frame can go on the wire: identifier within 11 bits (standard) or 29 bits
// (extended), payload length valid for its kind (valid_can_length). Ports drop others and
// count them in errors.
bool valid_can_frame(const CanFrameView& frame);

}  // namespace navemu::transport
