// Frame ports without kernel CAN: DLC table, slcan lines and the slcan port over a real pty,
// candump logs (checked with can-utils' log2asc), SocketCAN's error on a kernel without it.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "transports/can_port.hpp"

namespace navemu::transport {
namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

CanFrameView frame(std::uint32_t id, const std::vector<std::uint8_t>& data, bool extended = false,
                   bool fd = false, bool brs = false) {
  return CanFrameView{id, extended, fd, brs, data};
}

std::vector<std::uint8_t> counting_bytes(std::size_t n) {
  std::vector<std::uint8_t> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = static_cast<std::uint8_t>(i);
  return v;
}

// ---- DLC ------------------------------------------------------------------------------------

TEST(CanDlc, FollowsTheIso11898Table) {
  // ISO 11898-1:2015 DLC coding: 0..8 bytes, then 12, 16, 20, 24, 32, 48, 64 for DLC 9..15.
  const std::array<std::size_t, 16> length = {0, 1,  2,  3,  4,  5,  6,  7,
                                              8, 12, 16, 20, 24, 32, 48, 64};
  for (std::uint8_t dlc = 0; dlc < 16; ++dlc) {
    EXPECT_EQ(can_length_from_dlc(dlc), length[dlc]) << int{dlc};
    EXPECT_EQ(can_dlc_from_length(length[dlc]), dlc) << length[dlc];
  }
  // Lengths between the steps take the next bigger DLC (the frame is padded up to it).
  EXPECT_EQ(can_dlc_from_length(9), 9);
  EXPECT_EQ(can_dlc_from_length(13), 10);
  EXPECT_EQ(can_dlc_from_length(33), 14);
  EXPECT_EQ(can_dlc_from_length(49), 15);
  EXPECT_EQ(can_dlc_from_length(1000), 15);
  EXPECT_EQ(can_length_from_dlc(0x1F), 64u);  // only the 4 DLC bits count

  EXPECT_TRUE(valid_can_length(0, false));
  EXPECT_TRUE(valid_can_length(8, false));
  EXPECT_FALSE(valid_can_length(9, false));
  EXPECT_FALSE(valid_can_length(12, false));
  EXPECT_TRUE(valid_can_length(8, true));
  EXPECT_FALSE(valid_can_length(9, true));
  EXPECT_TRUE(valid_can_length(12, true));
  EXPECT_FALSE(valid_can_length(13, true));
  EXPECT_TRUE(valid_can_length(48, true));
  EXPECT_TRUE(valid_can_length(64, true));
  EXPECT_FALSE(valid_can_length(65, true));
}

// ---- slcan lines ----------------------------------------------------------------------------

std::string slcan_line(const CanFrameView& f) {
  std::string out = "stale";
  encode_slcan(f, out);
  return out;
}

TEST(SlcanEncode, ClassicFramesFollowTheLawicelCommands) {
  // The Lawicel/CAN232 manual's own examples: t00231199FF and t03F6112233445566.
  EXPECT_EQ(slcan_line(frame(0x002, {0x11, 0x99, 0xFF})), "t00231199FF\r");
  EXPECT_EQ(slcan_line(frame(0x03F, {0x11, 0x22, 0x33, 0x44, 0x55, 0x66})), "t03F6112233445566\r");
  EXPECT_EQ(slcan_line(frame(0x7FF, {})), "t7FF0\r");
  EXPECT_EQ(slcan_line(frame(0x0AB, {0xab, 0xcd})), "t0AB2ABCD\r");  // upper-case hex
  // Extended: 8 id digits (python-can reads id = line[1:9], dlc = line[9], data from line[10]).
  EXPECT_EQ(slcan_line(frame(0x18F02A80, {0x00, 0x11, 0x22, 0x33, 0x44, 0x55, 0x66, 0x77}, true)),
            "T18F02A8080011223344556677\r");
  EXPECT_EQ(slcan_line(frame(0x1, {0xFE}, true)), "T000000011FE\r");
}

TEST(SlcanEncode, FdFramesUseTheCanable2Letters) {
  // d/D without bit-rate switch, b/B with it; the DLC digit is the FD code in hex.
  EXPECT_EQ(slcan_line(frame(0x123, {0xAA, 0xBB, 0xCC, 0xDD, 0xEE}, false, true, true)),
            "b1235AABBCCDDEE\r");
  EXPECT_EQ(slcan_line(frame(0x510, counting_bytes(12), false, true, false)),
            "d5109000102030405060708090A0B\r");
  EXPECT_EQ(slcan_line(frame(0x1ABCDEF, counting_bytes(16), true, true, false)),
            "D01ABCDEFA000102030405060708090A0B0C0D0E0F\r");
  EXPECT_EQ(slcan_line(frame(0x1ABCDEF, counting_bytes(64), true, true, true)),
            "B01ABCDEFF"
            "000102030405060708090A0B0C0D0E0F101112131415161718191A1B1C1D1E1F"
            "202122232425262728292A2B2C2D2E2F303132333435363738393A3B3C3D3E3F\r");
}

// ---- slcan port over a pty ------------------------------------------------------------------

// An slcan port on a fresh pty and a client that holds the slave open in raw mode.
struct SlcanRig {
  std::string slave;
  std::unique_ptr<FramePort> port;
  int client = -1;

  explicit SlcanRig(SlcanOptions opt = {}) {
    auto pty = open_pty({});
    slave = pty_slave_path(*pty);
    port = open_slcan(std::move(pty), opt);
    client = ::open(slave.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (client < 0) throw std::runtime_error("open " + slave);
    termios tio{};
    ::tcgetattr(client, &tio);
    ::cfmakeraw(&tio);
    ::tcsetattr(client, TCSANOW, &tio);
  }
  ~SlcanRig() { ::close(client); }

  void send(const std::string& text) const {
    ASSERT_EQ(::write(client, text.data(), text.size()), static_cast<ssize_t>(text.size()));
  }

  // Services the port and collects what the client receives until nothing has come for
  // `quiet` (and at least `quiet` has passed).
  std::string receive(milliseconds quiet = milliseconds(60)) {
    std::string data;
    const auto deadline = Clock::now() + milliseconds(3000);
    auto last = Clock::now();
    char buf[1024];
    while (Clock::now() - last < quiet && Clock::now() < deadline) {
      port->service();
      pollfd p{client, POLLIN, 0};
      if (::poll(&p, 1, 2) <= 0) continue;
      const ssize_t n = ::read(client, buf, sizeof buf);
      if (n > 0) {
        data.append(buf, static_cast<std::size_t>(n));
        last = Clock::now();
      }
    }
    return data;
  }

  std::string command(const std::string& text) {
    send(text);
    return receive();
  }
};

TEST(SlcanPort, FramesFlowOnlyWhileTheChannelIsOpen) {
  SlcanRig rig;
  EXPECT_EQ(rig.port->describe(), "slcan on pty " + rig.slave);
  EXPECT_TRUE(rig.port->fd_capable());
  const std::vector<std::uint8_t> dead = {0xDE, 0xAD};

  // Closed at first: frames are held back (counted as such, not as dropped), nothing reaches
  // the client.
  EXPECT_FALSE(rig.port->write(frame(0x123, dead), 0));
  EXPECT_EQ(rig.receive(), "");
  EXPECT_EQ(rig.port->counters().frames_held, 1u);
  EXPECT_EQ(rig.port->counters().frames_dropped, 0u);

  // What python-can sends on opening: C, S6, O (one write); each is answered with CR.
  EXPECT_EQ(rig.command("C\rS6\rO\r"), "\r\r\r");
  EXPECT_EQ(rig.port->counters().commands, 3u);
  ASSERT_TRUE(rig.port->write(frame(0x123, dead), 0));
  ASSERT_TRUE(rig.port->write(frame(0x18F02A80, {1, 2, 3}, true), 0));
  ASSERT_TRUE(rig.port->write(frame(0x510, counting_bytes(12), false, true, true), 0));
  EXPECT_EQ(rig.receive(), "t1232DEAD\rT18F02A803010203\rb5109000102030405060708090A0B\r");
  EXPECT_EQ(rig.port->counters().frames_written, 3u);

  // Opening twice and changing the bit rate while open are errors.
  EXPECT_EQ(rig.command("O\r"), "\a");
  EXPECT_EQ(rig.command("S6\r"), "\a");
  EXPECT_EQ(rig.port->counters().errors, 2u);

  // Closed again: frames stop.
  EXPECT_EQ(rig.command("C\r"), "\r");
  EXPECT_FALSE(rig.port->write(frame(0x123, dead), 0));
  EXPECT_EQ(rig.receive(), "");
  EXPECT_EQ(rig.port->counters().frames_held, 2u);
  EXPECT_EQ(rig.port->counters().frames_dropped, 0u);
  EXPECT_EQ(rig.port->counters().frames_written, 3u);

  // Listen-only opens the channel too.
  EXPECT_EQ(rig.command("L\r"), "\r");
  ASSERT_TRUE(rig.port->write(frame(0x001, {}), 0));
  EXPECT_EQ(rig.receive(), "t0010\r");
}

TEST(SlcanPort, AutoOpenSendsFromTheStartUntilClosed) {
  SlcanRig rig(SlcanOptions{.auto_open = true});
  ASSERT_TRUE(rig.port->write(frame(0x7FF, {0x42}), 0));
  EXPECT_EQ(rig.receive(), "t7FF142\r");
  EXPECT_EQ(rig.command("C\r"), "\r");
  EXPECT_FALSE(rig.port->write(frame(0x7FF, {0x42}), 0));
  EXPECT_EQ(rig.receive(), "");
}

TEST(SlcanPort, AnswersQueriesAsAnAdapterDoes) {
  SlcanRig rig;
  // python-can's get_version() wants "V" + 4 digits + CR (hw 10, sw 13).
  EXPECT_EQ(rig.command("V\r"), "V1013\r");
  EXPECT_EQ(rig.command("v\r"), "vSTM32\r");
  EXPECT_EQ(rig.command("N\r"), "NNAVE\r");
  EXPECT_EQ(rig.command("F\r"), "F00\r");
  EXPECT_EQ(rig.command("Z1\r"), "\r");
  EXPECT_EQ(rig.command("s031C\r"), "\r");  // BTR0/BTR1 while closed
  EXPECT_EQ(rig.command("M00000000\rm FFFFFFFF\rX1\rW2\rQ0\r"), "\r\r\r\r\r");
  EXPECT_EQ(rig.port->counters().errors, 0u);

  // Unknown or malformed commands are answered with BEL and counted.
  EXPECT_EQ(rig.command("Y\r"), "\a");
  EXPECT_EQ(rig.command("S9\r"), "\a");
  EXPECT_EQ(rig.command("Z2\r"), "\a");
  EXPECT_EQ(rig.command("hello\r"), "\a");
  EXPECT_EQ(rig.command("s031\r"), "\a");
  EXPECT_EQ(rig.port->counters().errors, 5u);
  EXPECT_EQ(rig.port->counters().commands, 16u);

  // A line with no CR in sight is answered once; the next command works again.
  EXPECT_EQ(rig.command(std::string(300, 'A') + "\rV\r"), "\aV1013\r");
  EXPECT_EQ(rig.port->counters().errors, 6u);
  // Bare CRs (sent to clear an adapter's buffer) and CR LF line ends are harmless.
  EXPECT_EQ(rig.command("\r\r\rN\r\nF\r"), "NNAVE\rF00\r");
}

TEST(SlcanPort, FramesFromTheClientAreCheckedAndNotForwarded) {
  SlcanRig rig;
  EXPECT_EQ(rig.command("t1232AABB\r"), "\a");  // channel closed
  EXPECT_EQ(rig.command("O\r"), "\r");
  EXPECT_EQ(rig.command("t1232AABB\r"), "z\r");
  EXPECT_EQ(rig.command("T000001232AABB\r"), "Z\r");
  EXPECT_EQ(rig.command("r1232\rR1FFFFFFF8\r"), "z\rZ\r");
  EXPECT_EQ(rig.command("d5109000102030405060708090A0B\r"), "z\r");
  EXPECT_EQ(rig.command("B1FFFFFFF0\r"), "Z\r");
  // The longest command there is: an extended CAN FD frame with 64 bytes, 138 characters.
  std::string longest = "B1FFFFFFFF";
  for (int i = 0; i < 64; ++i) longest += "5A";
  ASSERT_EQ(longest.size(), 138u);
  EXPECT_EQ(rig.command(longest + "\r"), "Z\r");
  EXPECT_EQ(rig.command(longest + "5\r"), "\a");  // one character more than any command
  EXPECT_EQ(rig.port->counters().errors, 2u);
  EXPECT_EQ(rig.command("t1232AA\r"), "\a");            // one data byte short
  EXPECT_EQ(rig.command("t8000\r"), "\a");              // id beyond 11 bits
  EXPECT_EQ(rig.command("T200000000\r"), "\a");         // id beyond 29 bits
  EXPECT_EQ(rig.command("t1239\r"), "\a");              // DLC 9 in a classic frame
  EXPECT_EQ(rig.command("t12\r"), "\a");                // truncated
  EXPECT_EQ(rig.command("t1232AAZZ\r"), "\a");          // not hex
  EXPECT_EQ(rig.command("d1239000102030405\r"), "\a");  // DLC 9 is 12 bytes
  EXPECT_EQ(rig.port->counters().errors, 9u);
  EXPECT_EQ(rig.port->counters().frames_written, 0u);
}

TEST(SlcanPort, CommandsSplitAcrossWritesAreReassembled) {
  SlcanRig rig;
  rig.send("V");
  EXPECT_EQ(rig.receive(), "");  // no CR yet: no answer
  EXPECT_EQ(rig.command("\r"), "V1013\r");
  rig.send("C\rS");
  EXPECT_EQ(rig.receive(), "\r");
  rig.send("6\rO");
  EXPECT_EQ(rig.receive(), "\r");
  EXPECT_EQ(rig.command("\r"), "\r");
  // A frame command one byte at a time.
  for (const char c : std::string("T0000012")) {
    rig.send(std::string(1, c));
    rig.port->service();
  }
  EXPECT_EQ(rig.command("30\r"), "Z\r");  // T00000123, DLC 0
  EXPECT_EQ(rig.port->counters().errors, 0u);
  ASSERT_TRUE(rig.port->write(frame(0x100, {9}), 0));  // it is open now
  EXPECT_EQ(rig.receive(), "t100109\r");
}

TEST(SlcanPort, InvalidFramesAreDroppedAndCounted) {
  SlcanRig rig(SlcanOptions{.auto_open = true});
  EXPECT_FALSE(rig.port->write(frame(0x123, counting_bytes(9)), 0));  // classic, 9 bytes
  EXPECT_FALSE(rig.port->write(frame(0x123, counting_bytes(10), false, true), 0));  // FD, 10
  EXPECT_FALSE(rig.port->write(frame(0x123, counting_bytes(65), false, true), 0));  // FD, 65
  EXPECT_FALSE(rig.port->write(frame(0x800, {1}), 0));             // 12-bit standard id
  EXPECT_FALSE(rig.port->write(frame(0x20000000, {1}, true), 0));  // 30-bit extended id
  EXPECT_EQ(rig.port->counters().frames_failed, 5u);
  EXPECT_EQ(rig.port->counters().errors, 0u);  // no command was refused
  EXPECT_EQ(rig.port->counters().frames_written, 0u);
  EXPECT_EQ(rig.receive(), "");
}

// ---- candump log ----------------------------------------------------------------------------

std::string candump_line(const CanFrameView& f, std::int64_t t_ns, std::string_view iface) {
  std::string out = "stale";
  format_candump_line(f, t_ns, iface, out);
  return out;
}

TEST(CandumpLog, LinesAreInCandumpLFormat) {
  const std::int64_t t = 1700000000123456789;  // 2023-11-14T22:13:20.123456789Z
  EXPECT_EQ(candump_line(frame(0x123, {0xDE, 0xAD, 0xBE, 0xEF}), t, "vcan0"),
            "(1700000000.123456) vcan0 123#DEADBEEF\n");
  EXPECT_EQ(candump_line(frame(0x18F02A80, {0x00, 0x11, 0x22, 0x33, 0x44, 0x55, 0x66, 0x77}, true),
                         1700000000000001000, "can0"),
            "(1700000000.000001) can0 18F02A80#0011223344556677\n");
  EXPECT_EQ(candump_line(frame(0x7FF, {}), 5000000, "can0"), "(0000000000.005000) can0 7FF#\n");
  EXPECT_EQ(candump_line(frame(0x510, counting_bytes(12), false, true, true), t, "can0"),
            "(1700000000.123456) can0 510##1000102030405060708090A0B\n");
  EXPECT_EQ(candump_line(frame(0x1ABCDEF, {0xAB}, true, true, false), t, "can1"),
            "(1700000000.123456) can1 01ABCDEF##0AB\n");
  // An error frame: CAN_ERR_FLAG | class, 8 digits (can-utils lib.c sprint_canframe).
  const std::vector<std::uint8_t> zeros(8, 0);
  CanFrameView bus_off = frame(0x040, zeros);
  bus_off.error = true;
  EXPECT_EQ(candump_line(bus_off, t, "can0"), "(1700000000.123456) can0 20000040#0000000000000000\n");
}

std::filesystem::path temp_file(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         ("navemu-can-" + std::to_string(::getpid()) + "-" + name);
}

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(CandumpLog, WrittenLogIsReadByLog2asc) {
  if (!std::filesystem::exists("/usr/bin/log2asc")) GTEST_SKIP() << "can-utils log2asc missing";
  const auto log = temp_file("frames.log");
  const auto asc = temp_file("frames.asc");
  std::filesystem::remove(log);
  std::filesystem::remove(asc);
  {
    auto port = open_candump_log({log.string(), "can0"});
    EXPECT_EQ(port->describe(), "candump log " + log.string());
    EXPECT_TRUE(port->fd_capable());
    std::int64_t t = 1700000000000000000;
    ASSERT_TRUE(port->write(frame(0x123, {0xDE, 0xAD, 0xBE, 0xEF}), t += 10000000));
    ASSERT_TRUE(port->write(frame(0x18F02A80, counting_bytes(8), true), t += 10000000));
    ASSERT_TRUE(port->write(frame(0x7FF, {}), t += 10000000));
    ASSERT_TRUE(port->write(frame(0x510, counting_bytes(64), false, true, true), t += 10000000));
    ASSERT_TRUE(port->write(frame(0x1ABCDEF, counting_bytes(12), true, true), t += 10000000));
    EXPECT_FALSE(port->write(frame(0x123, counting_bytes(9)), t));  // invalid: not logged
    EXPECT_EQ(port->counters().frames_written, 5u);
    EXPECT_EQ(port->counters().frames_failed, 1u);
    port->service();
    EXPECT_EQ(slurp(log).substr(0, 38), "(1700000000.010000) can0 123#DEADBEEF\n");
  }
  const std::string cmd = "/usr/bin/log2asc -I " + log.string() + " -O " + asc.string() + " can0";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  std::istringstream in(slurp(asc));
  int frames = 0, fd_frames = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.find(" Rx ") == std::string::npos) continue;
    frames++;
    if (line.find("CANFD") != std::string::npos) fd_frames++;
  }
  EXPECT_EQ(frames, 5) << slurp(asc);
  EXPECT_EQ(fd_frames, 2) << slurp(asc);
  EXPECT_NE(slurp(asc).find("18F02A80x"), std::string::npos);  // extended ids marked x
  std::filesystem::remove(log);
  std::filesystem::remove(asc);
}

TEST(CandumpLog, DiskFullDropsFramesWithoutStopping) {
  testing::internal::CaptureStderr();
  {
    auto port = open_candump_log({"/dev/full", "can0"});
    EXPECT_TRUE(port->write(frame(0x1, {1}), 0));  // buffered
    port->service();                               // ENOSPC now
    EXPECT_FALSE(port->write(frame(0x1, {1}), 0));
    EXPECT_EQ(port->counters().frames_dropped, 1u);
  }
  EXPECT_NE(testing::internal::GetCapturedStderr().find("/dev/full"), std::string::npos);
}

// ---- SocketCAN without kernel CAN -----------------------------------------------------------

TEST(SocketCan, OpeningSaysTheKernelHasNoSocketCan) {
  if (socketcan_available()) GTEST_SKIP() << "this kernel has SocketCAN (see tests/vcan)";
  try {
    open_socketcan({"vcan0", false});
    FAIL() << "open_socketcan succeeded without SocketCAN";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(),
                 "socketcan vcan0: this kernel has no SocketCAN (socket(AF_CAN): Address family "
                 "not supported by protocol)");
  }
}

}  // namespace
}  // namespace navemu::transport
