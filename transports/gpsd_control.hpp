#pragma once
// gpsd's control socket (not part of the public transport interface).

#include <chrono>
#include <string>

namespace navemu::transport {

// Sends one command line to gpsd's control socket (gpsd -F PATH; gpsd(8), "GPS DEVICE
// MANAGEMENT": "+/dev/foo" adds a device to gpsd's pool, "-/dev/foo" removes it) and returns
// gpsd's answer, "OK" or "ERROR", or "" at once when `timeout` is zero. Throws
// std::runtime_error naming the socket when it cannot be reached or gpsd does not answer within
// `timeout`.
//
// gpsd 3.22 answers an add only after it has probed the device (about 2 s on a pty, by
// experiment), reading data from it meanwhile: a caller that is the device's source of data
// sends it with a zero timeout and goes on. gpsd serves nobody while a control connection is
// open, so the connection is closed as soon as the answer (or the command) is through.
std::string gpsd_control(const std::string& socket_path, const std::string& command,
                         std::chrono::milliseconds timeout);

}  // namespace navemu::transport
