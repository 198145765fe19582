#pragma once
// Byte transports: where a receiver's output goes and where a client's commands come from.
// Every port is non-blocking: write() never stalls the real-time loop. A chunk (one epoch's
// sentences or frames) is delivered whole or dropped whole and counted; a chunk that the
// kernel accepted only in part has its tail kept and sent first next time, so a client never
// sees a torn sentence. Output a client has not read for too long is discarded rather than
// delivered late (max_backlog_bytes).
//
// The OS specifics (pty, termios, libserialport, sockets) stay in the .cpp files.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>

namespace navemu::transport {

struct PortCounters {
  std::uint64_t chunks_written = 0;  // delivered whole (to at least one client)
  std::uint64_t bytes_written = 0;
  std::uint64_t chunks_dropped = 0;  // nobody could take them (buffer full, no client)
  std::uint64_t bytes_dropped = 0;
  std::uint64_t stale_flushes = 0;          // times unread output was discarded as stale
  std::uint64_t stale_bytes_flushed = 0;    // what those discarded, as far as it was counted
  std::uint64_t bytes_read = 0;             // from clients (commands)
  std::uint64_t clients_connected = 0;      // connections accepted / reopenings seen so far
  std::uint64_t errors = 0;                 // I/O errors other than "would block"
  std::uint64_t clients_refused = 0;        // TCP connections over max_clients, closed at once
  std::uint64_t client_chunks_dropped = 0;  // TCP: chunks one client could not take while
                                            // others may have (its buffer stayed full)
};

class BytePort {
 public:
  virtual ~BytePort() = default;
  // Queues one chunk; never blocks. Returns false when the chunk was dropped.
  virtual bool write(std::span<const std::uint8_t> chunk) = 0;
  bool write(std::string_view text) {
    return write(std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(text.data()),
                                               text.size()));
  }
  // Bytes the client(s) sent since the last call, at most buf.size(); never blocks.
  virtual std::size_t read(std::span<std::uint8_t> buf) = 0;
  // Housekeeping between epochs: accept connections, notice hang-ups, finish pending tails.
  virtual void service() {}
  // One line for the user: "pty /tmp/navemu-gnss -> /dev/pts/7", "tcp 127.0.0.1:2947".
  virtual std::string describe() const = 0;
  const PortCounters& counters() const { return counters_; }

 protected:
  PortCounters counters_;
};

// A pseudo-terminal: the slave in raw mode with mode 0666 (gpsd drops privileges after
// opening it), optionally reachable through a symlink. One port owns a link: it holds an
// exclusive flock(2) on LINK.lock beside it (a file with its pid in it) from before it creates
// the link until after it has removed it, so a second port on the same link is refused with
// "pty link LINK is in use by navemu (pid N)" and leaves the first one's link alone. The
// kernel drops the lock of a process that dies, so a link and lock file left by a killed
// instance are taken over. A link path that exists and is not a symlink is refused. The port
// keeps the slave open itself, so clients may close and reopen it at any time.
//
// gpsd: a pty's slave hangs up for good when the port closes, and gpsd 3.22 keeps such a
// device in its pool without ever reopening it, so after navemu restarts, gpsd stays silent.
// With gpsd_socket (gpsd's control socket, gpsd -F) the port tells gpsd as a hotplug script
// would (gpsd(8), "GPS DEVICE MANAGEMENT"): "-LINK" then "+LINK" once the link exists, and
// "-LINK" when the port closes; gpsd then reopens the new slave and its clients get fixes
// again without reconnecting. describe() tells whether gpsd was told; a gpsd that cannot be
// reached is not an error.
//
// Stale output: before each chunk the port asks the kernel how many bytes sit unread on the
// slave side (FIONREAD, plus what was written in the last few milliseconds, which the kernel
// reports late); when that plus the chunk would exceed max_backlog_bytes, the unread bytes are
// discarded (tcflush TCIFLUSH on the slave) and counted in stale_bytes_flushed (a lower
// bound), so a client never finds more than max_backlog_bytes of old output (or one chunk, if
// a chunk alone is bigger). The same happens when the tail of a partly written chunk is still
// stuck when the next chunk comes. Linux can only report up to 4095 unread bytes (the n_tty
// read buffer); anything beyond waits in buffers FIONREAD does not see, so a full read buffer
// always counts as stale and limits above about 4 KB act as about 4 KB. clients_connected
// counts opens of the slave by clients (inotify IN_OPEN; two opens with no close between them
// count once).
struct PtyOptions {
  std::string link_path;                 // empty: no symlink
  std::size_t max_backlog_bytes = 4096;  // unread output beyond this is flushed as stale
  std::string gpsd_socket = {};          // gpsd's control socket; empty: gpsd is not told
};
std::unique_ptr<BytePort> open_pty(const PtyOptions& opt);
// The slave device ("/dev/pts/7") of an open_pty() port; empty for any other port.
std::string pty_slave_path(const BytePort& port);

// A serial device through libserialport (8 data bits, no parity, 1 stop bit, no flow control),
// opened exclusively: the port takes an exclusive flock(2) on the device before configuring it
// (a device another program has locked is refused with "serial port DEVICE is in use by NAME
// (pid N)") and then sets TIOCEXCL (tty_ioctl(4)), so that later open(2)s of the device by
// other programs fail with EBUSY (root's excepted).
// libserialport looks devices up under /sys/class/tty, so it refuses ptys (/dev/pts/N): use
// open_pty() for those. A chunk that would leave more than max_backlog_bytes waiting in the
// output queue is dropped: when the baud rate is too low for the configured output, messages
// are lost (as on a real receiver) instead of arriving seconds late.
struct SerialOptions {
  std::string device;  // /dev/ttyUSB0
  int baud = 9600;
  std::size_t max_backlog_bytes = 4096;
};
std::unique_ptr<BytePort> open_serial(const SerialOptions& opt);
// Changes the baud rate of an open_serial() port (UBX CFG-PRT). The change waits until the
// output already queued (e.g. the ACK that confirms it) has left the port; chunks written
// meanwhile are dropped. Applied at once when nothing is pending, otherwise by a later
// write() or service(). False when `port` is not a serial port or `baud` is not positive.
bool set_serial_baud(BytePort& port, int baud);

// A TCP server: every connected client gets every chunk; commands from any client are read.
// Port 0 picks a free port (describe() tells which). service() accepts clients (those over
// max_clients are closed at once and counted) and notices hang-ups. A client with more than
// max_backlog_bytes not yet taken by the network (SIOCOUTQ) gets new chunks dropped, so a
// client that stops reading neither blocks the others nor later receives a flood of old data.
// read() takes the clients in turn, each one's bytes in one piece, so a command one client
// sent in two TCP segments may have another client's bytes between its halves.
struct TcpServerOptions {
  std::string bind_address = "127.0.0.1";  // numeric IPv4 or IPv6 ("::1", "0.0.0.0")
  int port = 0;
  int max_clients = 8;
  std::size_t max_backlog_bytes = 65536;
};
std::unique_ptr<BytePort> open_tcp_server(const TcpServerOptions& opt);
int tcp_server_port(const BytePort& port);   // bound port of an open_tcp_server() port, else -1
int tcp_client_count(const BytePort& port);  // clients connected now; 0 for other ports

// UDP: each chunk is one datagram to the destination (numeric IPv4 or IPv6 address).
struct UdpSenderOptions {
  std::string address = "127.0.0.1";
  int port = 0;
};
std::unique_ptr<BytePort> open_udp_sender(const UdpSenderOptions& opt);

// A log file (offline runs, mirrors of live output), appended to through a user-space buffer
// that is written out when full, by service() and on destruction; write errors (disk full)
// are counted, reported once on stderr, and never stop the caller.
std::unique_ptr<BytePort> open_log_file(const std::string& path);

// Whether a numeric address (or "localhost", or empty: the default) is a loopback address:
// 127.0.0.0/8, ::1 or ::ffff:127.x.x.x. Anything else (0.0.0.0, ::, a LAN address) can be
// reached from other hosts.
bool is_loopback_address(const std::string& address);

// Datagrams coming in (truth input). Binds to loopback unless told otherwise (an empty
// bind_address means 127.0.0.1).
class UdpReceiver {
 public:
  UdpReceiver(const std::string& bind_address, int port);  // port 0: any free port
  ~UdpReceiver();
  UdpReceiver(const UdpReceiver&) = delete;
  UdpReceiver& operator=(const UdpReceiver&) = delete;
  // The next datagram, or 0 when none is waiting; never blocks. Datagrams longer than
  // buf.size() are never returned: they are counted in truncated() and skipped (the call
  // goes on to the next datagram, a bounded number of times).
  std::size_t receive(std::span<std::uint8_t> buf);
  int port() const { return port_; }
  int fd() const { return fd_; }
  std::uint64_t truncated() const { return truncated_; }
  // Datagrams the kernel dropped before they could be read (the socket's queue was full), as
  // of the last one received (socket(7) SO_RXQ_OVFL).
  std::uint64_t kernel_dropped() const { return kernel_dropped_; }

 private:
  int fd_ = -1;
  int port_ = 0;
  std::uint64_t truncated_ = 0;
  std::uint64_t kernel_dropped_ = 0;
};

// Opening errors (missing or busy device, address in use, symlink path taken) throw
// std::runtime_error with a one-line message naming the device, path or address.

}  // namespace navemu::transport
