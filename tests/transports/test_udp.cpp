// UDP sender and receiver on loopback: round trip, truncation, kernel drops, opening errors.

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/socket.h>

#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "transports/byte_port.hpp"

namespace navemu::transport {
namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

// The next datagram that fits `size`, waiting up to a second; empty when none came.
std::string receive_one(UdpReceiver& rx, std::size_t size = 2048) {
  std::vector<std::uint8_t> buf(size);
  const auto deadline = Clock::now() + milliseconds(1000);
  while (Clock::now() < deadline) {
    const std::size_t n = rx.receive(buf);
    if (n > 0) return std::string(reinterpret_cast<const char*>(buf.data()), n);
    std::this_thread::sleep_for(milliseconds(1));
  }
  return {};
}

TEST(Udp, LoopbackAddresses) {
  for (const char* a : {"", "localhost", "127.0.0.1", "127.1.2.3", "::1", "::ffff:127.0.0.1"})
    EXPECT_TRUE(is_loopback_address(a)) << a;
  for (const char* a : {"0.0.0.0", "::", "192.168.1.10", "10.0.0.1", "::ffff:10.0.0.1", "fe80::1",
                        "128.0.0.1", "not an address"})
    EXPECT_FALSE(is_loopback_address(a)) << a;
}

TEST(Udp, SenderToReceiverRoundTrip) {
  UdpReceiver rx("127.0.0.1", 0);
  ASSERT_GT(rx.port(), 0);
  ASSERT_GE(rx.fd(), 0);
  auto tx = open_udp_sender({"127.0.0.1", rx.port()});
  EXPECT_EQ(tx->describe(), fmt::format("udp 127.0.0.1:{}", rx.port()));
  const std::vector<std::string> sent = {"$GPGGA,one*00\r\n", "$GPRMC,two*00\r\n",
                                         std::string(1400, 'x')};
  for (const std::string& s : sent) ASSERT_TRUE(tx->write(s));
  for (const std::string& s : sent) EXPECT_EQ(receive_one(rx), s);  // one datagram per chunk
  std::vector<std::uint8_t> buf(64);
  EXPECT_EQ(rx.receive(buf), 0u);  // nothing more, and no waiting
  EXPECT_EQ(tx->counters().chunks_written, 3u);
  EXPECT_EQ(tx->counters().errors, 0u);
  std::uint8_t rbuf[16];
  EXPECT_EQ(tx->read(rbuf), 0u);
}

TEST(Udp, TruncatedDatagramsAreCountedAndSkipped) {
  UdpReceiver rx("", 0);  // empty address: loopback
  auto tx = open_udp_sender({"127.0.0.1", rx.port()});
  ASSERT_TRUE(tx->write(std::string(100, 'a')));
  // Only a 10-byte buffer: the datagram is not returned, it is counted.
  std::vector<std::uint8_t> small(10);
  const auto deadline = Clock::now() + milliseconds(1000);
  while (rx.truncated() == 0 && Clock::now() < deadline) {
    EXPECT_EQ(rx.receive(small), 0u);
    std::this_thread::sleep_for(milliseconds(1));
  }
  EXPECT_EQ(rx.truncated(), 1u);
  // A long one followed by a short one: the short one comes back, the long one is counted.
  ASSERT_TRUE(tx->write(std::string(100, 'b')));
  ASSERT_TRUE(tx->write(std::string(5, 'c')));
  std::this_thread::sleep_for(milliseconds(5));
  EXPECT_EQ(receive_one(rx, 10), "ccccc");
  EXPECT_EQ(rx.truncated(), 2u);
}

// A queue too small for a burst: the kernel drops what does not fit, and the count it reports
// with the next datagram (SO_RXQ_OVFL) makes received + dropped = sent, exactly.
TEST(Udp, DatagramsTheKernelDroppedAreCounted) {
  UdpReceiver rx("127.0.0.1", 0);
  const int small_bytes = 4096;  // the kernel doubles it and keeps a floor: a few datagrams
  ASSERT_EQ(::setsockopt(rx.fd(), SOL_SOCKET, SO_RCVBUF, &small_bytes, sizeof small_bytes), 0);
  auto tx = open_udp_sender({"127.0.0.1", rx.port()});
  constexpr int kBurst = 500;
  for (int i = 0; i < kBurst; ++i) ASSERT_TRUE(tx->write(std::string(100, 'x')));
  std::vector<std::uint8_t> buf(2048);
  int received = 0;
  while (rx.receive(buf) > 0) ++received;
  // The drops after the last queued datagram are reported with the next one.
  ASSERT_TRUE(tx->write(std::string("last")));
  EXPECT_EQ(receive_one(rx), "last");
  ++received;
  EXPECT_GT(rx.kernel_dropped(), 0u) << received << " received";
  EXPECT_EQ(static_cast<std::uint64_t>(received) + rx.kernel_dropped(), kBurst + 1u);
}

TEST(Udp, Ipv6Loopback) {
  std::unique_ptr<UdpReceiver> rx;
  try {
    rx = std::make_unique<UdpReceiver>("::1", 0);
  } catch (const std::runtime_error& e) {
    GTEST_SKIP() << "no IPv6 loopback here: " << e.what();
  }
  auto tx = open_udp_sender({"::1", rx->port()});
  EXPECT_EQ(tx->describe(), fmt::format("udp [::1]:{}", rx->port()));
  ASSERT_TRUE(tx->write(std::string_view("v6")));
  EXPECT_EQ(receive_one(*rx), "v6");
}

TEST(Udp, OpeningErrorsNameTheAddress) {
  try {
    UdpReceiver rx("999.1.1.1", 5000);
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("udp 999.1.1.1:5000: ", 0), 0u) << e.what();
  }
  UdpReceiver first("127.0.0.1", 0);
  try {
    UdpReceiver second("127.0.0.1", first.port());
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()),
              fmt::format("udp 127.0.0.1:{}: address already in use", first.port()));
  }
  EXPECT_THROW(open_udp_sender({"127.0.0.1", 0}), std::runtime_error);
  EXPECT_THROW(open_udp_sender({"not-an-address", 5000}), std::runtime_error);
}

TEST(Udp, OversizedChunkIsCountedNotThrown) {
  UdpReceiver rx("127.0.0.1", 0);
  auto tx = open_udp_sender({"127.0.0.1", rx.port()});
  EXPECT_FALSE(tx->write(std::string(70000, 'z')));  // over the 65507-byte UDP payload limit
  EXPECT_EQ(tx->counters().chunks_dropped, 1u);
  EXPECT_EQ(tx->counters().errors, 1u);
  EXPECT_TRUE(tx->write(std::string_view("after")));
  EXPECT_EQ(receive_one(rx), "after");
}

}  // namespace
}  // namespace navemu::transport
