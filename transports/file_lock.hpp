#pragma once
// One owner per port: exclusive advisory locks (flock(2)) on pty link lock files and serial
// devices, and an owned file descriptor (not part of the public transport interface).

#include <unistd.h>

#include <string>

namespace navemu::transport {

// Owns a file descriptor and closes it.
struct Fd {
  int fd = -1;
  Fd() = default;
  explicit Fd(int f) : fd(f) {}
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

// flock(fd, LOCK_EX | LOCK_NB): true when this open file now holds the lock, false when another
// open file (in this or another process) holds it; throws std::runtime_error (prefixed with
// `what`) on any other error.
bool try_lock_exclusive(int fd, const std::string& what);

// Who holds a flock(2) lock on the file open as `fd`: "navemu (pid 4242)", from /proc/locks
// (proc(5): the holder's pid and the device and inode of the locked file) and /proc/PID/comm;
// "another process" when /proc does not tell.
std::string lock_holder(int fd);

}  // namespace navemu::transport
