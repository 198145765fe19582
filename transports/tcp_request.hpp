#pragma once
// A one-shot line exchange with a TCP server (navemu ctl with a running navemu's control port):
// connect to a numeric address, send the lines, read `expected` reply lines or until the
// timeout, close.

#include <string>
#include <vector>

namespace navemu::transport {

// The reply lines (without newlines) that arrived within timeout_s; std::runtime_error when the
// server cannot be reached.
std::vector<std::string> tcp_request_lines(const std::string& address, int port, const std::vector<std::string>& lines,
                                           std::size_t expected, double timeout_s);

}  // namespace navemu::transport
