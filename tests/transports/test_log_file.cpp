// The log file port: buffered append, disk-full handling, opening errors.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "transports/byte_port.hpp"

namespace navemu::transport {
namespace {

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::filesystem::path temp_file(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         ("navemu-log-" + std::to_string(::getpid()) + "-" + name);
}

TEST(LogFile, AppendsChunksInOrder) {
  const auto path = temp_file("append.log");
  std::filesystem::remove(path);
  {
    auto log = open_log_file(path.string());
    EXPECT_EQ(log->describe(), "log " + path.string());
    ASSERT_TRUE(log->write(std::string_view("$GPGGA,1*00\r\n")));
    ASSERT_TRUE(log->write(std::string_view("$GPRMC,2*00\r\n")));
    log->service();  // written out between epochs
    EXPECT_EQ(slurp(path), "$GPGGA,1*00\r\n$GPRMC,2*00\r\n");
    ASSERT_TRUE(log->write(std::string_view("\xb5\x62 binary\0 too", 14)));
  }  // the rest on destruction
  {
    auto log = open_log_file(path.string());  // appends, never truncates
    ASSERT_TRUE(log->write(std::string_view("more")));
    EXPECT_EQ(log->counters().chunks_written, 1u);
  }
  EXPECT_EQ(slurp(path),
            std::string("$GPGGA,1*00\r\n$GPRMC,2*00\r\n\xb5\x62 binary\0 toomore", 44));
  std::filesystem::remove(path);
}

TEST(LogFile, ChunksBiggerThanTheBufferArriveWhole) {
  const auto path = temp_file("big.log");
  std::filesystem::remove(path);
  std::string expected;
  {
    auto log = open_log_file(path.string());
    for (int i = 0; i < 5; ++i) {
      const std::string chunk(30000 * static_cast<std::size_t>(i + 1), static_cast<char>('a' + i));
      ASSERT_TRUE(log->write(chunk));
      expected += chunk;
    }
    EXPECT_EQ(log->counters().errors, 0u);
  }
  EXPECT_EQ(slurp(path), expected);
  std::filesystem::remove(path);
}

TEST(LogFile, DiskFullIsCountedAndReportedOnce) {
  testing::internal::CaptureStderr();
  {
    auto log = open_log_file("/dev/full");                   // every write(2) fails with ENOSPC
    EXPECT_TRUE(log->write(std::string_view("first\r\n")));  // buffered: not known yet
    log->service();
    EXPECT_EQ(log->counters().errors, 1u);
    EXPECT_FALSE(log->write(std::string_view("second\r\n")));
    EXPECT_FALSE(log->write(std::string(100000, 'x')));
    log->service();
    EXPECT_EQ(log->counters().errors, 1u);
    EXPECT_EQ(log->counters().chunks_dropped, 2u);
    EXPECT_EQ(log->counters().bytes_written, 0u);
  }
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(err,
            "navemu: log /dev/full: No space left on device; further output to it is dropped\n");
}

TEST(LogFile, OpeningErrorNamesThePath) {
  const std::string path = "/nonexistent-navemu-dir/out.log";
  try {
    open_log_file(path);
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace navemu::transport
