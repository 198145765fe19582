// No allocation in the emulator's steady-state loop (issue: real-time hardening).
//
// This binary replaces the global operator new to count every allocation. The same
// configuration runs for a short and a long duration: setup and wrap-up are identical, so the
// difference in allocations is what the extra seconds of the loop allocated, and it must be
// zero. A first run warms up what is built once per process (the geoid grid, profile caches). Offline runs (simulate: the same loop and encoders plus the CSV files) cover hours of
// scenario in a second; a real-time run covers the sleeping, port and lateness code.

#include <gtest/gtest.h>

#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <new>
#include <sstream>
#include <streambuf>
#include <thread>

#include "emulator/commands.hpp"
#include "emulator/engine.hpp"
#include "emulator/geoid_loader.hpp"
#include "emulator/run_config.hpp"
#include "emulator/truth_buffer.hpp"

namespace {
std::atomic<long long> g_allocations{0};
}

void* operator new(std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) { return ::operator new(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(n ? n : 1);
}
void* operator new[](std::size_t n, const std::nothrow_t& t) noexcept { return ::operator new(n, t); }
void* operator new(std::size_t n, std::align_val_t a) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  const std::size_t al = static_cast<std::size_t>(a);
  if (void* p = std::aligned_alloc(al, (n + al - 1) / al * al)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n, std::align_val_t a) { return ::operator new(n, a); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

namespace navemu {
namespace {

long long allocations_of_run(const RunConfig& cfg, bool realtime, double duration_s,
                             const std::filesystem::path& out) {
  EngineOptions opt;
  opt.realtime = realtime;
  opt.duration_s = duration_s;
  opt.out_dir = out;
  std::ostringstream log;
  const GpsTime start = parse_time("2010-11-17T13:00:00Z");
  const long long before = g_allocations.load();
  const EngineSummary s = run_engine(cfg, start, opt, log);
  const long long n = g_allocations.load() - before;
  EXPECT_GT(s.gnss_epochs, 0) << log.str();
  EXPECT_TRUE(!cfg.imu_enabled || s.imu_samples > 0) << log.str();
  std::filesystem::remove_all(out);
  return n;
}

RunConfig config(const char* name) {
  return load_run_config(std::filesystem::path(NAVEMU_SOURCE_DIR) / "configs" / name);
}

// Offline runs of 600 s and 1800 s (after a warm-up run) allocate the same.
void expect_offline_steady_state(const RunConfig& cfg, const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("navemu_alloc_" + name);
  allocations_of_run(cfg, false, 10.0, dir / "warm-up");
  const long long a = allocations_of_run(cfg, false, 600.0, dir / "a");
  const long long b = allocations_of_run(cfg, false, 1800.0, dir / "b");
  std::printf("%s: %lld allocations for 600 s, %lld for 1800 s\n", name.c_str(), a, b);
  EXPECT_EQ(b - a, 0);
}

TEST(SteadyStateAllocation, OfflineDefaultConfiguration) {
  expect_offline_steady_state(config("default.yaml"), "default");
}

TEST(SteadyStateAllocation, OfflineUbxEveryMessage) {
  RunConfig cfg = config("ublox-f9p.yaml");
  ASSERT_TRUE(cfg.gnss.ubx);
  cfg.gnss.ubx->messages.clear();
  for (const std::string& m : known_ubx_outputs()) cfg.gnss.ubx->messages.emplace_back(m, 1);
  // With impairments that come and go in both runs: satellites lost and re-acquired.
  cfg.gnss_events.jamming = {JammingEvent{{100.0, 300.0, 60.0}, 40.0, InterferenceKind::kWideband, Band::kL1}};
  cfg.gnss_events.outages = {OutageEvent{{420.0, 30.0, 0.0}, 90.0, 270.0, 40.0}};
  cfg.gnss_events.antenna = {AntennaEvent{{470.0, 10.0, 0.0}, AntennaFault::kShort}};
  // And impairments that last from 200 s to the end of either run.
  const EventWindow on{200.0, 1e5, 20.0};
  cfg.gnss_events.satellites = {SatelliteFaultEvent{{500.0, 60.0, 20.0}, gps_sat(5), 30.0},
                                SatelliteFaultEvent{on, gps_sat(7), 0.0, Vec3(5, 20, 1), true}};
  cfg.gnss_events.spoofing = {SpoofingEvent{on, Vec3(0, 100, 0)}};
  cfg.gnss_events.ionosphere = {IonosphereEvent{on, 5.0}};
  cfg.gnss_events.multipath = {MultipathEvent{on, 3.0}};
  cfg.gnss_events.cable = {CableEvent{{540.0, 5.0}}};
  cfg.gnss_events.resets = {ResetEvent{{560.0, 1.5}, RestartKind::kHot}};
  expect_offline_steady_state(cfg, "ublox-f9p");
}

// The default job with IMU and truth faults that last from 100 s to the end of either run.
TEST(SteadyStateAllocation, OfflineImuAndTruthFaults) {
  RunConfig cfg = config("default.yaml");
  const EventWindow w{100.0, 1e5, 10.0};
  ImuFault vibration{w, ImuFaultKind::kVibration, ImuSensor::kAccel, -1, 0.5};
  vibration.vibration = {20.0, 0.01, 5.0, 50.0};
  cfg.imu_faults = {vibration,
                    {w, ImuFaultKind::kSaturation, ImuSensor::kGyro, 2, 0.01},
                    {w, ImuFaultKind::kTemperature, ImuSensor::kGyro, -1, 20.0},
                    {w, ImuFaultKind::kNoise, ImuSensor::kGyro, 0, 0.01},
                    {w, ImuFaultKind::kDuplicate, ImuSensor::kGyro, -1, 0.3},
                    {w, ImuFaultKind::kDrop, ImuSensor::kGyro, -1, 0.3},
                    {w, ImuFaultKind::kErrorFrames, ImuSensor::kGyro, -1, 20.0},
                    {EventWindow{150.0, 10.0}, ImuFaultKind::kBusOff, ImuSensor::kGyro, -1, 0.0}};
  cfg.truth_faults = {TruthFault{EventWindow{300.0, 20.0}, TruthFaultKind::kFreeze},
                      TruthFault{EventWindow{350.0, 1e5}, TruthFaultKind::kTeleport, Vec3(0, 50, 0)},
                      TruthFault{EventWindow{400.0, 1e5}, TruthFaultKind::kTimeJump, Vec3::Zero(), 3.0}};
  expect_offline_steady_state(cfg, "imu-truth-faults");
}

// The built-in constellation renews its data sets once a day (models/measurement.cpp): a
// GNSS-only run of 25 h, which renews after 24 h, allocates what one of 10 min does; with GPS
// alone, and with all five systems (Galileo and BeiDou made anew, GLONASS integrated on, into
// the storage of the sets before).
void expect_renewal_allocates_nothing(std::uint32_t systems, const char* name) {
  RunConfig cfg = config("default.yaml");
  cfg.imu_enabled = false;
  cfg.gnss.rate_hz = 1.0;
  cfg.gnss.systems = systems;
  const auto dir = std::filesystem::temp_directory_path() / (std::string("navemu_alloc_renewal_") + name);
  allocations_of_run(cfg, false, 10.0, dir / "warm-up");
  const long long a = allocations_of_run(cfg, false, 600.0, dir / "a");
  const long long b = allocations_of_run(cfg, false, 25 * 3600.0, dir / "b");
  std::printf("renewal (%s): %lld allocations for 600 s, %lld for 25 h\n", name, a, b);
  EXPECT_EQ(b - a, 0);
}
TEST(SteadyStateAllocation, OfflineDailyRenewalOfTheBuiltInConstellation) {
  expect_renewal_allocates_nothing(system_bit(GnssSystem::kGps), "gps");
}
TEST(SteadyStateAllocation, OfflineDailyRenewalOfEverySystem) {
  std::uint32_t all = 0;
  for (GnssSystem s : {GnssSystem::kGps, GnssSystem::kGalileo, GnssSystem::kBeidou, GnssSystem::kQzss,
                       GnssSystem::kGlonass})
    all |= system_bit(s);
  expect_renewal_allocates_nothing(all, "five-systems");
}

// The truth stream (UDP datagrams) at 1 kHz through its buffer: once the 10 s window is full,
// pushing and interpolating allocate nothing.
TEST(SteadyStateAllocation, TruthBufferAtOneKilohertz) {
  TruthBuffer buffer(1.0, 10.0);
  ImuTruth s;
  s.position = Geodetic{32.3, -90.9, 60.0};
  const auto feed = [&](std::int64_t from, std::int64_t to) {
    for (std::int64_t k = from; k < to; ++k) {
      s.t = GpsTime{k * 1'000'000};
      s.position.lat_deg = 32.3 + 1e-9 * static_cast<double>(k);
      EXPECT_EQ(buffer.push(s), TruthVerdict::kAccepted);
      EXPECT_TRUE(buffer.at(GpsTime{k * 1'000'000 - 500'000}).has_value() || k == 0);
    }
  };
  feed(0, 30'000);  // 30 s: the window fills and the buffer compacts a few times
  const long long before = g_allocations.load();
  feed(30'000, 90'000);
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_LE(buffer.size(), 10'002u);
}

// The geoid of the MSL heights is in memory once loaded: a vehicle crossing grid cells (an
// aircraft crosses a 15' cell every two minutes) reads no file and allocates nothing. Here a
// sweep over the globe, every cell of it visited.
TEST(SteadyStateAllocation, GeoidAnywhereOnTheGlobe) {
  const LoadedGeoid& geoid = egm96_geoid();
  ASSERT_TRUE(geoid.grid) << geoid.description;
  const long long before = g_allocations.load();
  double sum_m = 0.0;
  for (double lat = -90.0; lat <= 90.0; lat += 0.1)
    for (double lon = -180.0; lon < 180.0; lon += 0.1) sum_m += geoid.grid->separation_m(lat, lon);
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_TRUE(std::isfinite(sum_m));
}

// A log that discards what it is given without allocating (an ostringstream would grow).
struct NullBuffer : std::streambuf {
  int overflow(int c) override { return c; }
  std::streamsize xsputn(const char*, std::streamsize n) override { return n; }
};

// Real time, as `navemu run`: GNSS NMEA and UBX on a pty drained by a reader (a client), the
// IMU's CAN frames into a candump log, the IMU sample log, and a status line every second.
TEST(SteadyStateAllocation, RealTimeRun) {
  const auto dir = std::filesystem::temp_directory_path() / "navemu_alloc_rt";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  RunConfig cfg = config("ublox-f9p.yaml");
  cfg.gnss.ubx->messages = {{"NAV-PVT", 1}, {"NAV-SAT", 1}, {"RXM-RAWX", 1}};
  cfg.gnss.rate_hz = 5.0;
  OutputSpec pty;
  pty.type = "pty";
  pty.link = (dir / "gnss").string();
  cfg.gnss_outputs = {pty};
  cfg.gnss_capture.clear();
  CanOutputSpec can;
  can.type = "candump";
  can.path = (dir / "imu.candump").string();
  can.interface = "vcan0";
  can.layouts = {CanLayout::kJ1939, CanLayout::kHighRes};
  cfg.imu_outputs = {can};
  cfg.imu_log = (dir / "imu.csv").string();
  cfg.status_interval_s = 1.0;
  // IMU faults active through most of each run (the drop short: the sample counts below).
  cfg.imu_faults = {{{0.2, 10.0, 0.5}, ImuFaultKind::kBias, ImuSensor::kGyro, 2, 0.01},
                    {{0.2, 10.0, 0.5}, ImuFaultKind::kNoise, ImuSensor::kAccel, -1, 0.01},
                    {{0.2, 10.0, 0.0}, ImuFaultKind::kStuck, ImuSensor::kGyro, 0, 0.0},
                    {{0.3, 0.1, 0.0}, ImuFaultKind::kDrop, ImuSensor::kGyro, -1, 0.5}};

  std::atomic<bool> done{false};
  std::atomic<long long> bytes_read{0};
  std::thread reader([&] {  // bounded: stops when told, polls at most every 50 ms
    int fd = -1;
    std::array<char, 4096> buf{};
    while (!done.load()) {
      if (fd < 0) fd = ::open(pty.link.c_str(), O_RDONLY | O_NOCTTY | O_NONBLOCK);
      if (fd < 0) {
        ::usleep(10'000);
        continue;
      }
      pollfd p{fd, POLLIN, 0};
      if (::poll(&p, 1, 50) > 0) {
        const ssize_t n = ::read(fd, buf.data(), buf.size());
        if (n > 0) bytes_read += n;
        if (n == 0 || (n < 0 && errno != EAGAIN)) {  // the writer's run ended: reopen
          ::close(fd);
          fd = -1;
        }
      }
    }
    if (fd >= 0) ::close(fd);
  });
  NullBuffer null_buffer;
  std::ostream log(&null_buffer);
  const auto run = [&](double duration_s) {
    EngineOptions opt;
    opt.duration_s = duration_s;
    const long long before = g_allocations.load();
    const EngineSummary s = run_engine(cfg, gps_now(), opt, log);
    const long long n = g_allocations.load() - before;
    EXPECT_GE(s.gnss_epochs, static_cast<std::int64_t>(duration_s * 5.0) - 2);
    EXPECT_GE(s.imu_samples, static_cast<std::int64_t>(duration_s * 125.0) - 20);
    return n;
  };
  run(0.5);  // warm-up
  const long long a = run(2.0);
  const long long b = run(5.0);
  done = true;
  reader.join();
  std::printf("real time: %lld allocations for 2 s, %lld for 5 s; client read %lld bytes\n", a, b,
              bytes_read.load());
  EXPECT_GT(bytes_read.load(), 10'000);
  EXPECT_EQ(b - a, 0);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace navemu
