// Log file port: append-only file with a user-space buffer (open(2) O_APPEND, write(2)).

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "transports/byte_port.hpp"

namespace navemu::transport {
namespace {

constexpr std::size_t kBufferSize = 64 * 1024;  // written out when full, by service(), at close

class LogFile final : public BytePort {
 public:
  explicit LogFile(const std::string& path) : path_(path) {
    fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (fd_ < 0)
      throw std::runtime_error(
          fmt::format("log {}: cannot open: {}", path,
                      std::error_code(errno, std::generic_category()).message()));
    buf_.reserve(kBufferSize);
  }

  ~LogFile() override {
    flush();
    ::close(fd_);
  }
  LogFile(const LogFile&) = delete;
  LogFile& operator=(const LogFile&) = delete;

  using BytePort::write;

  bool write(std::span<const std::uint8_t> chunk) override {
    if (chunk.empty()) return true;
    if (!failed_ && buf_.size() + chunk.size() > kBufferSize) flush();
    if (failed_) {
      counters_.chunks_dropped++;
      counters_.bytes_dropped += chunk.size();
      return false;
    }
    if (chunk.size() >= kBufferSize)
      write_all(chunk.data(), chunk.size());  // bigger than the buffer: straight to the file
    else
      buf_.insert(buf_.end(), chunk.begin(), chunk.end());  // within the reserved capacity
    counters_.chunks_written++;
    return true;
  }

  std::size_t read(std::span<std::uint8_t>) override { return 0; }

  // Between epochs: write the buffer out, so a live mirror can be followed (tail -f).
  void service() override { flush(); }

  std::string describe() const override { return "log " + path_; }

 private:
  void flush() {
    if (buf_.empty()) return;
    write_all(buf_.data(), buf_.size());
    buf_.clear();
  }

  // write(2) until everything is out; the first error (ENOSPC, EIO, EFBIG) is counted and
  // reported once, and everything after it is dropped.
  void write_all(const std::uint8_t* data, std::size_t size) {
    while (size > 0 && !failed_) {
      const ssize_t n = ::write(fd_, data, size);
      if (n > 0) {
        data += n;
        size -= static_cast<std::size_t>(n);
        counters_.bytes_written += static_cast<std::uint64_t>(n);
      } else if (n < 0 && errno == EINTR) {
        continue;
      } else {
        const int e = n < 0 ? errno : EIO;
        failed_ = true;
        counters_.errors++;
        std::fputs(fmt::format("navemu: log {}: {}; further output to it is dropped\n", path_,
                               std::error_code(e, std::generic_category()).message())
                       .c_str(),
                   stderr);
      }
    }
    counters_.bytes_dropped += size;
  }

  std::string path_;
  int fd_ = -1;
  std::vector<std::uint8_t> buf_;
  bool failed_ = false;
};

}  // namespace

std::unique_ptr<BytePort> open_log_file(const std::string& path) {
  return std::make_unique<LogFile>(path);
}

}  // namespace navemu::transport
