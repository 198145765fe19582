// Serial device port through libserialport (sigrok.org/wiki/Libserialport, 0.1.1 API).
//
// libserialport on Linux resolves a device by reading /sys/class/tty/<name> and refuses
// names it does not find there: /dev/pts/N (no sysfs entry) and symlinks outside /dev give
// SP_ERR_ARG from sp_get_port_by_name(); /dev/ptmx is found but sp_open() then fails with
// ENOTTY (a pty has no modem-control lines for TIOCMGET). Ptys therefore go through pty.cpp.

#include <fcntl.h>
#include <fmt/format.h>
#include <libserialport.h>
#include <sys/ioctl.h>
#include <sys/stat.h>

#include <cerrno>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "transports/byte_port.hpp"
#include "transports/file_lock.hpp"

namespace navemu::transport {
namespace {

constexpr std::size_t kTailReserve = 8 * 1024;  // pending-tail buffer, reserved once

// libserialport's text for its last OS error (freed here).
std::string sp_error_text() {
  char* msg = sp_last_error_message();
  std::string text = msg != nullptr ? msg : "unknown error";
  sp_free_error_message(msg);
  return text;
}

// The error for a device that cannot be opened (errno `code`, libserialport's or the OS's
// `text`).
std::runtime_error open_error(const std::string& what, int code, const std::string& text) {
  if (code == EBUSY)
    return std::runtime_error(what + ": busy (in use by another program): " + text);
  if (code == EACCES)
    return std::runtime_error(what + ": permission denied (is the user in group dialout?)");
  return std::runtime_error(what + ": cannot open: " + text);
}

class SerialPort final : public BytePort {
 public:
  explicit SerialPort(const SerialOptions& opt)
      : device_(opt.device), baud_(opt.baud), max_backlog_(opt.max_backlog_bytes) {
    const std::string what = fmt::format("serial port {}", device_);
    if (opt.baud <= 0)
      throw std::runtime_error(fmt::format("{}: bad baud rate {}", what, opt.baud));
    struct stat st {};
    if (::stat(device_.c_str(), &st) != 0) {
      if (errno == ENOENT) throw std::runtime_error(what + ": no such device");
      throw std::runtime_error(
          fmt::format("{}: {}", what, std::error_code(errno, std::generic_category()).message()));
    }
    // One owner: an exclusive flock(2) on the device before libserialport configures it (its
    // settings are the tty's, shared by every open file of it).
    lock_.fd = ::open(device_.c_str(), O_RDONLY | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (lock_.fd < 0)
      throw open_error(what, errno, std::error_code(errno, std::generic_category()).message());
    if (!try_lock_exclusive(lock_.fd, what))
      throw std::runtime_error(fmt::format("{} is in use by {}", what, lock_holder(lock_.fd)));
    if (sp_get_port_by_name(device_.c_str(), &port_) != SP_OK || port_ == nullptr)
      throw std::runtime_error(what +
                               ": not a serial device known to libserialport (it looks devices up "
                               "in /sys/class/tty; for a pty use the pty output)");
    if (sp_open(port_, SP_MODE_READ_WRITE) != SP_OK) {
      const int code = sp_last_error_code();
      const std::string text = sp_error_text();
      sp_free_port(port_);
      port_ = nullptr;
      throw open_error(what, code, text);
    }
    // 8N1 without flow control: what GNSS receivers and IMUs speak.
    if (sp_set_baudrate(port_, baud_) != SP_OK || sp_set_bits(port_, 8) != SP_OK ||
        sp_set_parity(port_, SP_PARITY_NONE) != SP_OK || sp_set_stopbits(port_, 1) != SP_OK ||
        sp_set_flowcontrol(port_, SP_FLOWCONTROL_NONE) != SP_OK) {
      const std::string text = sp_error_text();
      close_port();
      throw std::runtime_error(fmt::format("{}: cannot set {} baud 8N1: {}", what, baud_, text));
    }
    // From now on other programs' open(2)s of the device fail with EBUSY (tty_ioctl(4)
    // TIOCEXCL; root can still open it). Best effort: the flock above is the rule.
    ::ioctl(lock_.fd, TIOCEXCL);
    tail_.reserve(kTailReserve);
  }

  ~SerialPort() override { close_port(); }
  SerialPort(const SerialPort&) = delete;
  SerialPort& operator=(const SerialPort&) = delete;

  using BytePort::write;

  bool write(std::span<const std::uint8_t> chunk) override {
    if (chunk.empty()) return true;
    if (!flush_tail() || !apply_pending_baud()) return drop(chunk.size());
    // Whole chunk or nothing, and no more than max_backlog_ bytes waiting to go out.
    const int waiting = sp_output_waiting(port_);
    if (waiting > 0 && static_cast<std::size_t>(waiting) + chunk.size() > max_backlog_)
      return drop(chunk.size());
    const int n = sp_nonblocking_write(port_, chunk.data(), chunk.size());
    if (n < 0) counters_.errors++;
    if (n <= 0) return drop(chunk.size());
    const auto sent = static_cast<std::size_t>(n);
    counters_.chunks_written++;
    counters_.bytes_written += sent;
    if (sent < chunk.size()) {
      tail_.assign(chunk.begin() + static_cast<std::ptrdiff_t>(sent), chunk.end());
      tail_off_ = 0;
    }
    return true;
  }

  std::size_t read(std::span<std::uint8_t> buf) override {
    if (buf.empty()) return 0;
    const int n = sp_nonblocking_read(port_, buf.data(), buf.size());
    if (n < 0) counters_.errors++;
    if (n <= 0) return 0;
    counters_.bytes_read += static_cast<std::uint64_t>(n);
    return static_cast<std::size_t>(n);
  }

  void service() override {
    if (flush_tail()) apply_pending_baud();
  }

  std::string describe() const override { return fmt::format("serial {} {} baud", device_, baud_); }

  bool request_baud(int baud) {
    if (baud <= 0) return false;
    pending_baud_ = baud;
    if (flush_tail()) apply_pending_baud();
    return true;
  }

 private:
  void close_port() {
    if (port_ == nullptr) return;
    sp_close(port_);
    sp_free_port(port_);
    port_ = nullptr;
  }

  // Sends what is left of a partly written chunk; true when nothing is left.
  bool flush_tail() {
    if (tail_off_ >= tail_.size()) return true;
    const int n = sp_nonblocking_write(port_, tail_.data() + tail_off_, tail_.size() - tail_off_);
    if (n > 0) {
      tail_off_ += static_cast<std::size_t>(n);
      counters_.bytes_written += static_cast<std::uint64_t>(n);
    } else if (n < 0) {
      counters_.errors++;
      counters_.bytes_dropped += tail_.size() - tail_off_;
      tail_off_ = tail_.size();
    }
    if (tail_off_ < tail_.size()) return false;
    tail_.clear();
    tail_off_ = 0;
    return true;
  }

  // Applies a requested baud rate once the output queue and the transmitter are empty (so the
  // ACK of a CFG-PRT leaves at the old rate); true when no change is pending any more.
  bool apply_pending_baud() {
    if (pending_baud_ == 0) return true;
    if (sp_output_waiting(port_) > 0) return false;
    // TIOCSERGETLSR (tty_ioctl(4)) tells whether the UART's shift register is empty too; USB
    // adapters mostly do not implement it, and then the empty queue has to do.
    int fd = -1;
    unsigned int lsr = 0;
    if (sp_get_port_handle(port_, &fd) == SP_OK && ::ioctl(fd, TIOCSERGETLSR, &lsr) == 0 &&
        (lsr & TIOCSER_TEMT) == 0)
      return false;
    if (sp_set_baudrate(port_, pending_baud_) == SP_OK)
      baud_ = pending_baud_;
    else
      counters_.errors++;
    pending_baud_ = 0;
    return true;
  }

  bool drop(std::size_t size) {
    counters_.chunks_dropped++;
    counters_.bytes_dropped += size;
    return false;
  }

  Fd lock_;  // holds the flock(2) on the device (opened before, closed after port_)
  sp_port* port_ = nullptr;
  std::string device_;
  int baud_;
  int pending_baud_ = 0;  // requested by set_serial_baud(), not yet applied
  std::size_t max_backlog_;
  std::vector<std::uint8_t> tail_;  // unsent end of the last chunk, reserved once
  std::size_t tail_off_ = 0;
};

}  // namespace

std::unique_ptr<BytePort> open_serial(const SerialOptions& opt) {
  return std::make_unique<SerialPort>(opt);
}

bool set_serial_baud(BytePort& port, int baud) {
  auto* serial = dynamic_cast<SerialPort*>(&port);
  return serial != nullptr && serial->request_baud(baud);
}

}  // namespace navemu::transport
