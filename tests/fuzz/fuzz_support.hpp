#pragma once
// Shared pieces of the fuzz targets (tests/fuzz/README.md): each target defines
// LLVMFuzzerTestOneInput, the libFuzzer entry point, and holds the one property every input must
// keep: the reader either accepts it or rejects it with the error it documents (navemu's
// InputError naming file and line, or a decode result). Any other exception escaping, a crash,
// a hang or a sanitizer report is a finding.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>
#include <string_view>

#include <unistd.h>

#include <algorithm>

#include "transports/byte_port.hpp"

namespace navemu::fuzz {

inline std::span<const std::uint8_t> bytes_of(const std::uint8_t* data, std::size_t size) {
  return {data, size};
}
inline std::string_view text_of(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// The readers that take a path get the input through a file of this process's own, in a
// folder of its own (a configuration's relative paths resolve there), rewritten per input and
// removed when the process exits normally (libFuzzer exits at the end of its time).
inline const std::filesystem::path& scratch_dir() {
  // Never destroyed, so that the exit handler can still use it.
  static const std::filesystem::path* const dir = [] {
    const char* tmp = std::getenv("TMPDIR");
    auto* d = new std::filesystem::path(std::filesystem::path(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") /
                                        ("navemu-fuzz-" + std::to_string(::getpid())));
    std::filesystem::create_directories(*d);
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(scratch_dir(), ec);
    });
    return d;
  }();
  return *dir;
}

inline std::filesystem::path write_scratch(const std::string& name, std::string_view text) {
  const std::filesystem::path file = scratch_dir() / name;
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  return file;
}

// A finding that is not a crash by itself (a broken round trip): report and abort, so that
// libFuzzer saves the input.
[[noreturn]] inline void fail(const char* what) {
  std::fprintf(stderr, "navemu fuzz: %s\n", what);
  std::abort();
}

// A byte port in memory: its client "sent" `pending` (read() hands it out in order), and what
// the reader writes back collects in `written`.
class MemoryPort final : public transport::BytePort {
 public:
  bool write(std::span<const std::uint8_t> chunk) override {
    written.append(reinterpret_cast<const char*>(chunk.data()), chunk.size());
    return true;
  }
  std::size_t read(std::span<std::uint8_t> buf) override {
    const std::size_t n = std::min(buf.size(), pending.size());
    std::copy_n(pending.begin(), n, buf.begin());
    pending = pending.subspan(n);
    return n;
  }
  std::string describe() const override { return "memory"; }

  std::span<const std::uint8_t> pending;
  std::string written;
};

}  // namespace navemu::fuzz
