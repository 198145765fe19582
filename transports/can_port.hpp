#pragma once
// Frame transports: where CAN frames go. Like the byte ports, every frame port is non-blocking:
// write() never stalls the real-time loop; a frame the port cannot take now is dropped and
// counted. The SocketCAN headers stay in socketcan.cpp.
//
// Frames here are plain identifier + payload (transports know no protocols); protocols/
// can_frames.hpp builds them.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "transports/byte_port.hpp"

namespace navemu::transport {

struct CanFrameView {
  std::uint32_t id = 0;  // 11-bit or 29-bit identifier, no flag bits; an error frame's class
  bool extended = false;
  bool fd = false;  // CAN FD frame (payload 0..8, 12, 16, 20, 24, 32, 48 or 64 bytes)
  bool brs = false;  // CAN FD bit-rate switch
  std::span<const std::uint8_t> data;
  // A SocketCAN error frame (linux/can/error.h): id holds its error class bits (CAN_ERR_BUSOFF,
  // CAN_ERR_PROT | CAN_ERR_BUSERROR, ...), 8 data bytes; only ports with carries_error_frames().
  bool error = false;
};

struct CanCounters {
  std::uint64_t frames_written = 0;
  std::uint64_t frames_dropped = 0;  // queue full (ENOBUFS/EAGAIN), no reader
  std::uint64_t frames_held = 0;     // slcan: not sent because no client has opened the channel
  std::uint64_t frames_failed = 0;   // not sent for another reason: invalid, interface down, ...
                                     // (written + dropped + held + failed = every frame offered)
  std::uint64_t bus_errors = 0;      // error frames received from the interface
  std::uint64_t errors = 0;          // I/O errors (interface went down, ...); slcan: commands
                                     // answered with BEL
  std::uint64_t commands = 0;        // slcan: commands received from the client
};

class FramePort {
 public:
  virtual ~FramePort() = default;
  // Sends one frame; never blocks. `unix_time_ns` (nanoseconds since 1970-01-01 UTC) stamps
  // the frame in logs; live ports ignore it. False when the frame was dropped.
  virtual bool write(const CanFrameView& frame, std::int64_t unix_time_ns) = 0;
  // Frames sent back to back (one IMU sample's); never blocks. How many were sent. By default
  // one write() each; SocketCAN hands them to the kernel in one call.
  virtual std::size_t write_burst(std::span<const CanFrameView> frames, std::int64_t unix_time_ns) {
    std::size_t sent = 0;
    for (const CanFrameView& f : frames) sent += write(f, unix_time_ns) ? 1u : 0u;
    return sent;
  }
  // Housekeeping between frames: read error frames or client commands, flush buffers.
  virtual void service() {}
  // One line for the user: "socketcan vcan0", "slcan pty /tmp/navemu-imu -> /dev/pts/4".
  virtual std::string describe() const = 0;
  // Whether CAN FD frames can be sent here.
  virtual bool fd_capable() const = 0;
  // Whether error frames can be sent here (SocketCAN, candump logs; not slcan, whose protocol
  // has none).
  virtual bool carries_error_frames() const { return false; }
  const CanCounters& counters() const { return counters_; }

 protected:
  CanCounters counters_;
};

// Valid CAN FD payload lengths: 0..8, 12, 16, 20, 24, 32, 48, 64. The DLC code of a length
// (ISO 11898-1:2015 table 5), and back.
bool valid_can_length(std::size_t len, bool fd);
std::uint8_t can_dlc_from_length(std::size_t len);
std::size_t can_length_from_dlc(std::uint8_t dlc);

// ---- SocketCAN raw socket -------------------------------------------------------------------
// A CAN_RAW socket bound to one interface (vcan0, can0). Opening checks, each with its own
// one-line error: SocketCAN present in the kernel (socket(AF_CAN) fails with EAFNOSUPPORT on
// kernels without it), the interface exists, is a CAN interface, is up, and (fd) has the CAN FD
// MTU (72; the bigger CAN XL MTU carries CAN FD frames too). The socket is non-blocking and receives nothing but error frames (CAN_RAW_FILTER
// empty, CAN_RAW_ERR_FILTER all), which service() reads and counts as bus errors. A write that
// fails with ENOBUFS or EAGAIN (transmit queue full) drops the frame and counts it; ENETDOWN
// (interface went down) counts an error, and sending resumes when it comes up again.
struct SocketCanOptions {
  std::string interface;  // vcan0, can0
  bool fd = false;        // enable CAN FD frames (CAN_RAW_FD_FRAMES)
};
std::unique_ptr<FramePort> open_socketcan(const SocketCanOptions& opt);
// Whether this kernel offers SocketCAN at all (socket(AF_CAN, SOCK_RAW, CAN_RAW) succeeds).
bool socketcan_available();

// ---- slcan (Lawicel ASCII) ------------------------------------------------------------------
// Frames as a USB-CAN adapter in slcan mode sends them, over a byte port (pty or serial):
//   tIIILDD..\r        standard frame: 3 hex id digits, DLC digit, 2 hex digits per byte
//   TIIIIIIIILDD..\r   extended frame: 8 hex id digits
//   dIIIL.. / DIIIIIIIIL..   CAN FD frame (no bit-rate switch), DLC digit 0..F
//   bIIIL.. / BIIIIIIIIL..   CAN FD frame with bit-rate switch
// (Lawicel CAN232/CANUSB command set; the FD letters as in the CANable 2 firmware). Upper-case
// hex. Frames flow while the channel is open: the client opens it with "O\r" and closes it with
// "C\r" (python-can's slcan interface sends C, S<n>, O on opening), unless auto_open is set,
// in which case frames flow from the start. Commands from the client are answered as an
// adapter does: "\r" for success, "\a" (BEL) for an error;
//   O, L (listen only)   open the channel; error when already open
//   C                    close the channel
//   Sn (n 0..8), sXXYY   set the bit rate; only while closed
//   V / v / N            version "V1013\r" / "vSTM32\r" / serial number "NNAVE\r"
//   F                    status flags "F00\r"
//   Z0 / Z1              time stamps off / on (accepted; frames carry none)
//   t T d D b B r R      frames from the client: accepted while open ("z\r" / "Z\r"), not
//                        forwarded
//   M, m, X, W, Q        accepted with "\r" (filters, auto-poll, mode: no effect here)
// Anything else, or a line over 138 characters (the longest command, a 64-byte extended CAN FD
// frame) without CR, is answered with BEL and counted in errors. Empty lines (clients send CRs
// to clear an adapter's input) get no answer. Frames dropped while the channel is closed count
// in frames_dropped.
struct SlcanOptions {
  bool auto_open = false;
};
std::unique_ptr<FramePort> open_slcan(std::unique_ptr<BytePort> port, const SlcanOptions& opt);
// Encodes one frame as its slcan line (with the trailing \r) into `out` (cleared first).
void encode_slcan(const CanFrameView& frame, std::string& out);

// ---- candump log ----------------------------------------------------------------------------
// can-utils' `candump -L` format, one frame per line:
//   (1700000000.123456) vcan0 123#DEADBEEF
//   (1700000000.123456) vcan0 18F02A80#0011223344556677      extended: 8 hex id digits
//   (1700000000.123456) vcan0 510##1<128 hex digits>         CAN FD: ## and a flags nibble
//                                                             (1 = BRS, 2 = ESI)
// The time stamp is the frame's unix_time_ns in microseconds. Written through the same
// buffered log file as open_log_file (disk full is reported once, never stops the caller).
struct CandumpLogOptions {
  std::string path;
  std::string interface_name = "can0";  // the interface column
};
std::unique_ptr<FramePort> open_candump_log(const CandumpLogOptions& opt);
// One frame as its candump -L line (with the trailing \n) into `out` (cleared first).
void format_candump_line(const CanFrameView& frame, std::int64_t unix_time_ns,
                         std::string_view interface_name, std::string& out);

}  // namespace navemu::transport
