// flock(2) and /proc/locks (proc(5)) for the ports' one-owner rule (file_lock.hpp).

#include "transports/file_lock.hpp"

#include <fmt/format.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>

#include <cerrno>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>

namespace navemu::transport {

bool try_lock_exclusive(int fd, const std::string& what) {
  int r;
  do r = ::flock(fd, LOCK_EX | LOCK_NB);
  while (r != 0 && errno == EINTR);
  if (r == 0) return true;
  if (errno == EWOULDBLOCK) return false;
  throw std::runtime_error(fmt::format("{}: flock: {}", what,
                                       std::error_code(errno, std::generic_category()).message()));
}

std::string lock_holder(int fd) {
  struct stat st {};
  if (::fstat(fd, &st) != 0) return "another process";
  // A line of /proc/locks: "1: FLOCK  ADVISORY  WRITE 4242 00:1a:5678 0 EOF" (ordinal, kind,
  // mode, access, pid, major:minor:inode of the locked file in hex:hex:decimal, range). Lines
  // with "->" are processes waiting for a lock, not holding it.
  const std::string file_id =
      fmt::format("{:02x}:{:02x}:{}", major(st.st_dev), minor(st.st_dev), st.st_ino);
  std::ifstream locks("/proc/locks");
  for (std::string line; std::getline(locks, line);) {
    std::istringstream in(line);
    std::string ordinal, kind, mode, access, id;
    long pid = 0;
    if (!(in >> ordinal >> kind >> mode >> access >> pid >> id) || kind != "FLOCK" ||
        id != file_id || pid <= 0)
      continue;
    std::string comm;
    std::getline(std::ifstream(fmt::format("/proc/{}/comm", pid)), comm);
    return fmt::format("{} (pid {})", comm.empty() ? "a process" : comm, pid);
  }
  return "another process";
}

}  // namespace navemu::transport
