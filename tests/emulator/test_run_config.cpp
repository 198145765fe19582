// Run configurations and GNSS profiles: the shipped files load, and bad files fail with the
// file, line and key.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "emulator/run_config.hpp"
#include "core/errors.hpp"

namespace navemu {
namespace {

// One folder per test: ctest runs the tests of this file in parallel, and they reuse names.
std::filesystem::path write_temp(const std::string& name, const std::string& text) {
  const auto dir = std::filesystem::temp_directory_path() / "navemu_run_config_test" /
                   ::testing::UnitTest::GetInstance()->current_test_info()->name();
  std::filesystem::create_directories(dir);
  const auto p = dir / name;
  std::ofstream(p) << text;
  return p;
}

std::string load_error(const std::string& yaml) {
  try {
    load_run_config(write_temp("bad.yaml", yaml));
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(RunConfig, DefaultConfigIsThePapersCircleWithTheGarminReceiverOnAPty) {
  const RunConfig c = load_run_config(default_run_config());
  EXPECT_EQ(c.truth.kind, TruthSourceKind::kCircle);
  EXPECT_NEAR(c.truth.circle.radius_m, 9.144, 1e-9);  // 30 ft
  EXPECT_NEAR(c.truth.circle.center.lat_deg, 32.3, 1e-9);
  EXPECT_EQ(c.gnss.name, "garmin-18x-5hz");
  EXPECT_DOUBLE_EQ(c.gnss.rate_hz, 5.0);
  ASSERT_EQ(c.gnss_outputs.size(), 1u);
  EXPECT_EQ(c.gnss_outputs[0].type, "pty");
  EXPECT_EQ(c.gnss_outputs[0].link, "/tmp/navemu-gnss");
  EXPECT_EQ(c.imu_profile, "paper_phidget");
  EXPECT_EQ(c.time_mode, TimeMode::kRealTime);
  // The IMU on vcan0 as J1939, an slcan pty when vcan0 cannot be opened.
  ASSERT_EQ(c.imu_outputs.size(), 1u);
  EXPECT_EQ(c.imu_outputs[0].type, "socketcan");
  EXPECT_EQ(c.imu_outputs[0].interface, "vcan0");
  EXPECT_EQ(c.imu_outputs[0].layouts, std::vector<CanLayout>{CanLayout::kJ1939});
  ASSERT_EQ(c.imu_outputs[0].fallback.size(), 1u);
  EXPECT_EQ(c.imu_outputs[0].fallback[0].type, "slcan");
  EXPECT_EQ(c.imu_outputs[0].fallback[0].link, "/tmp/navemu-imu");
  EXPECT_EQ(c.imu_can.source_address, 0x80);  // written 0x80 in the file
  EXPECT_EQ(c.imu_can.priority, 3);
  EXPECT_EQ(c.imu_can.base_id, 0x500u);
}

TEST(RunConfig, RealtimeHardening) {
  EXPECT_FALSE(load_run_config(default_run_config()).cpu);
  const RunConfig c = load_run_config(
      write_temp("rt.yaml", "realtime: {sched_fifo: true, lock_memory: true, cpu: 1}\n"));
  EXPECT_TRUE(c.sched_fifo);
  EXPECT_TRUE(c.lock_memory);
  EXPECT_EQ(c.cpu, 1);
  const std::string e = load_error("realtime:\n  cpu: -1\n");
  EXPECT_NE(e.find("bad.yaml:2"), std::string::npos) << e;
  EXPECT_NE(e.find("cpu"), std::string::npos) << e;
}

TEST(RunConfig, CanOutputsAndLayouts) {
  const RunConfig c = load_run_config(write_temp(
      "can.yaml",
      "imu:\n  can:\n    j1939: {priority: 6, source_address: 226}\n"
      "    highres: {base_id: 0x18FF0000, extended: true}\n  outputs:\n"
      "    - {type: candump, path: imu.log, layouts: [highres, highres-fd, j1939]}\n"
      "    - {type: slcan, device: /dev/ttyACM0, baud: 921600, auto_open: true}\n"));
  EXPECT_EQ(c.imu_can.priority, 6);
  EXPECT_EQ(c.imu_can.source_address, 226);
  EXPECT_EQ(c.imu_can.base_id, 0x18FF0000u);
  EXPECT_TRUE(c.imu_can.extended);
  ASSERT_EQ(c.imu_outputs.size(), 2u);
  EXPECT_EQ(c.imu_outputs[0].layouts,
            (std::vector<CanLayout>{CanLayout::kHighRes, CanLayout::kHighResFd, CanLayout::kJ1939}));
  EXPECT_EQ(c.imu_outputs[0].interface, "can0");
  EXPECT_EQ(c.imu_outputs[1].device, "/dev/ttyACM0");
  EXPECT_EQ(c.imu_outputs[1].baud, 921600);
  EXPECT_TRUE(c.imu_outputs[1].auto_open);
}

TEST(RunConfig, BadCanSettingsNameTheKey) {
  const auto err = [](const std::string& yaml) { return load_error("imu:\n" + yaml); };
  EXPECT_NE(err("  can:\n    j1939: {source_address: 254}\n")
                .find(":3: imu.can.j1939.source_address: 254 outside [0, 253]"),
            std::string::npos)
      << err("  can:\n    j1939: {source_address: 254}\n");
  EXPECT_NE(err("  can:\n    j1939: {priority: 8}\n").find("imu.can.j1939.priority: 8 outside [0, 7]"),
            std::string::npos);
  EXPECT_NE(err("  can:\n    highres: {base_id: 0x7F0}\n").find("imu.can.highres.base_id: 2032 outside"),
            std::string::npos);
  EXPECT_NE(err("  outputs:\n    - {type: socketcan, interface: vcan0, layouts: [nmea2000]}\n")
                .find("imu.outputs[0].layouts: 'nmea2000' is not one of j1939, highres, highres-fd"),
            std::string::npos)
      << err("  outputs:\n    - {type: socketcan, interface: vcan0, layouts: [nmea2000]}\n");
  EXPECT_NE(err("  outputs:\n    - {type: socketcan}\n").find("imu.outputs[0].interface: required"),
            std::string::npos);
  EXPECT_NE(err("  outputs:\n    - {type: isotp}\n").find("'isotp' is not one of socketcan, slcan, candump"),
            std::string::npos);
  EXPECT_NE(err("  outputs:\n    - {type: slcan, fallback: {type: candump, path: x}}\n")
                .find("only a socketcan output has a fallback"),
            std::string::npos);
  EXPECT_NE(err("  outputs:\n    - {type: candump}\n").find("imu.outputs[0].path: required"),
            std::string::npos);
}

// `events:` schedules impairments; a bad entry names its line and key.
TEST(RunConfig, EventsAndTheirErrors) {
  const RunConfig c = load_run_config(write_temp(
      "events.yaml",
      "events:\n"
      "  - {type: jamming, start_s: 60, duration_s: 120, ramp_s: 30, j_over_s_db: 40}\n"
      "  - {type: jamming, duration_s: 5, j_over_s_db: 55.5, kind: cw, band: L5}\n"
      "  - {type: outage, start_s: 10, duration_s: 20}\n"
      "  - {type: outage, start_s: 40, duration_s: 20, azimuth_deg: [300, 60], below_elevation_deg: 45}\n"
      "  - {type: antenna, start_s: 5, duration_s: 2, fault: short}\n"
      "  - {type: satellite, start_s: 50, duration_s: 100, ramp_s: 50, prn: 7, clock_error_m: 80}\n"
      "  - {type: satellite, duration_s: 10, prn: 9, orbit_error_m: [5, -20, 3], unhealthy: true}\n"
      "  - {type: ionosphere, start_s: 30, duration_s: 600, ramp_s: 120, scale: 6}\n"
      "  - {type: multipath, duration_s: 60, scale: 3.5}\n"
      "  - {type: cable, start_s: 5, duration_s: 2}\n"
      "  - {type: reset, start_s: 8, start: warm}\n"
      "  - {type: reset, at: '2394:475300'}\n"
      "  - {type: truth, start_s: 3, duration_s: 2, fault: freeze}\n"
      "  - {type: truth, start_s: 3, duration_s: 2, fault: teleport, offset_m: [1, -2, 3]}\n"
      "  - {type: truth, start_s: 3, duration_s: 2, fault: time_jump, jump_s: -1.5}\n"
      "  - {type: imu, start_s: 3, duration_s: 4, ramp_s: 1, fault: bias, sensor: gyro, axis: z, bias_dps: 180}\n"
      "  - {type: imu, duration_s: 4, fault: bias, sensor: accel, bias_mps2: -0.5}\n"
      "  - {type: imu, duration_s: 4, fault: scale, sensor: accel, axis: y, scale_ppm: 2000}\n"
      "  - {type: imu, duration_s: 4, fault: noise, sensor: gyro, noise_radps_per_rthz: 0.01}\n"
      "  - {type: imu, duration_s: 4, fault: stuck, sensor: gyro, axis: x}\n"
      "  - {type: imu, duration_s: 4, fault: drop, probability: 0.25}\n"
      "  - {type: imu, duration_s: 4, fault: saturation, sensor: gyro, axis: y, range_dps: 90}\n"
      "  - {type: imu, duration_s: 4, fault: vibration, sensor: gyro, amplitude_dps: 2, frequency_hz: 30, "
      "psd_dps2_per_hz: 0.5, band_hz: [20, 80]}\n"
      "  - {type: imu, duration_s: 4, fault: vibration, sensor: accel, psd_g2_per_hz: 0.04, band_hz: [20, 200]}\n"
      "  - {type: imu, duration_s: 40, ramp_s: 20, fault: temperature, temperature_c: -30}\n"
      "  - {type: imu, duration_s: 4, fault: duplicate, probability: 0.1}\n"
      "  - {type: imu, duration_s: 4, fault: bus_off}\n"
      "  - {type: imu, duration_s: 4, ramp_s: 1, fault: error_frames, rate_hz: 40}\n"
      "  - {type: outage, at: '2394:475200.5', duration_s: 20}\n"
      "  - {type: spoofing, start_s: 10, duration_s: 60, ramp_s: 20, offset_m: [0, 500, -5], power_advantage_db: 1.5}\n"
      "  - {type: spoofing, start_s: 10, duration_s: 60, time_offset_s: -0.25}\n"));
  ASSERT_EQ(c.gnss_events.spoofing.size(), 2u);
  EXPECT_EQ(c.gnss_events.spoofing[0].time_offset_s, 0.0);
  EXPECT_EQ(c.gnss_events.spoofing[1].time_offset_s, -0.25);
  EXPECT_EQ(c.gnss_events.spoofing[1].offset_enu_m, Vec3::Zero());
  EXPECT_EQ(c.gnss_events.spoofing[0].offset_enu_m, Vec3(0, 500, -5));
  EXPECT_EQ(c.gnss_events.spoofing[0].power_advantage_db, 1.5);
  EXPECT_EQ(c.gnss_events.spoofing[0].window.ramp_s, 20.0);
  ASSERT_EQ(c.imu_faults.size(), 13u);
  EXPECT_EQ(c.imu_faults[0].kind, ImuFaultKind::kBias);
  EXPECT_EQ(c.imu_faults[0].sensor, ImuSensor::kGyro);
  EXPECT_EQ(c.imu_faults[0].axis, 2);
  EXPECT_NEAR(c.imu_faults[0].value, 3.14159265358979, 1e-12) << "180 deg/s in rad/s";
  EXPECT_EQ(c.imu_faults[0].window.ramp_s, 1.0);
  EXPECT_EQ(c.imu_faults[1].sensor, ImuSensor::kAccel);
  EXPECT_EQ(c.imu_faults[1].axis, -1) << "all axes by default";
  EXPECT_EQ(c.imu_faults[1].value, -0.5);
  EXPECT_EQ(c.imu_faults[2].kind, ImuFaultKind::kScale);
  EXPECT_EQ(c.imu_faults[2].axis, 1);
  EXPECT_EQ(c.imu_faults[2].value, 2000.0);
  EXPECT_EQ(c.imu_faults[3].kind, ImuFaultKind::kNoise);
  EXPECT_EQ(c.imu_faults[3].value, 0.01);
  EXPECT_EQ(c.imu_faults[4].kind, ImuFaultKind::kStuck);
  EXPECT_EQ(c.imu_faults[5].kind, ImuFaultKind::kDrop);
  EXPECT_EQ(c.imu_faults[5].value, 0.25);
  constexpr double kDeg = 3.14159265358979323846 / 180.0, kG = 9.80665;
  EXPECT_EQ(c.imu_faults[6].kind, ImuFaultKind::kSaturation);
  EXPECT_NEAR(c.imu_faults[6].value, 90.0 * kDeg, 1e-15);
  EXPECT_EQ(c.imu_faults[7].kind, ImuFaultKind::kVibration);
  EXPECT_NEAR(c.imu_faults[7].value, 2.0 * kDeg, 1e-15);
  EXPECT_EQ(c.imu_faults[7].vibration.frequency_hz, 30.0);
  EXPECT_NEAR(c.imu_faults[7].vibration.psd, 0.5 * kDeg * kDeg, 1e-15) << "(deg/s)^2/Hz in (rad/s)^2/Hz";
  EXPECT_EQ(c.imu_faults[7].vibration.band_lo_hz, 20.0);
  EXPECT_EQ(c.imu_faults[7].vibration.band_hi_hz, 80.0);
  EXPECT_EQ(c.imu_faults[8].value, 0.0) << "no sinusoid";
  EXPECT_NEAR(c.imu_faults[8].vibration.psd, 0.04 * kG * kG, 1e-12) << "g^2/Hz in (m/s^2)^2/Hz";
  EXPECT_EQ(c.imu_faults[9].kind, ImuFaultKind::kTemperature);
  EXPECT_EQ(c.imu_faults[9].value, -30.0);
  EXPECT_EQ(c.imu_faults[9].window.ramp_s, 20.0);
  EXPECT_EQ(c.imu_faults[10].kind, ImuFaultKind::kDuplicate);
  EXPECT_EQ(c.imu_faults[10].value, 0.1);
  EXPECT_EQ(c.imu_faults[11].kind, ImuFaultKind::kBusOff);
  EXPECT_EQ(c.imu_faults[12].kind, ImuFaultKind::kErrorFrames);
  EXPECT_EQ(c.imu_faults[12].value, 40.0);
  const GnssEvents& e = c.gnss_events;
  ASSERT_EQ(e.jamming.size(), 2u);
  EXPECT_EQ(e.jamming[0].window.start_s, 60.0);
  EXPECT_EQ(e.jamming[0].window.duration_s, 120.0);
  EXPECT_EQ(e.jamming[0].window.ramp_s, 30.0);
  EXPECT_EQ(e.jamming[0].j_over_s_db, 40.0);
  EXPECT_EQ(e.jamming[0].kind, InterferenceKind::kWideband);
  EXPECT_EQ(e.jamming[0].band, Band::kL1);
  EXPECT_EQ(e.jamming[1].window.start_s, 0.0);
  EXPECT_EQ(e.jamming[1].kind, InterferenceKind::kCw);
  EXPECT_EQ(e.jamming[1].band, Band::kL5);
  ASSERT_EQ(e.outages.size(), 3u);
  ASSERT_TRUE(e.outages[2].window.at.has_value());
  EXPECT_EQ(*e.outages[2].window.at, parse_time("2394:475200.5"));
  EXPECT_EQ(e.outages[0].below_el_deg, 90.0) << "everything: a tunnel";
  EXPECT_EQ(e.outages[1].az_from_deg, 300.0);
  EXPECT_EQ(e.outages[1].az_to_deg, 60.0);
  EXPECT_EQ(e.outages[1].below_el_deg, 45.0);
  ASSERT_EQ(e.antenna.size(), 1u);
  EXPECT_EQ(e.antenna[0].fault, AntennaFault::kShort);
  EXPECT_EQ(e.antenna[0].window.duration_s, 2.0);
  ASSERT_EQ(e.satellites.size(), 2u);
  EXPECT_EQ(e.satellites[0].sat, gps_sat(7));
  EXPECT_EQ(e.satellites[0].clock_error_m, 80.0);
  EXPECT_EQ(e.satellites[0].window.ramp_s, 50.0);
  EXPECT_FALSE(e.satellites[0].unhealthy);
  EXPECT_EQ(e.satellites[1].clock_error_m, 0.0);
  EXPECT_EQ(e.satellites[1].orbit_error_rac_m, Vec3(5, -20, 3));
  EXPECT_TRUE(e.satellites[1].unhealthy);
  ASSERT_EQ(e.ionosphere.size(), 1u);
  EXPECT_EQ(e.ionosphere[0].scale, 6.0);
  EXPECT_EQ(e.ionosphere[0].window.ramp_s, 120.0);
  ASSERT_EQ(e.multipath.size(), 1u);
  EXPECT_EQ(e.multipath[0].scale, 3.5);
  ASSERT_EQ(e.cable.size(), 1u);
  EXPECT_EQ(e.cable[0].window.duration_s, 2.0);
  ASSERT_EQ(e.resets.size(), 2u);
  EXPECT_EQ(e.resets[0].kind, RestartKind::kWarm);
  EXPECT_EQ(e.resets[0].window.start_s, 8.0);
  EXPECT_EQ(e.resets[0].window.duration_s, 25.5) << "the boot and the warm start's 25 s";
  EXPECT_EQ(e.resets[1].kind, RestartKind::kCold) << "a power cycle without backup by default";
  EXPECT_TRUE(e.resets[1].window.at.has_value());
  ASSERT_EQ(c.truth_faults.size(), 3u);
  EXPECT_EQ(c.truth_faults[0].kind, TruthFaultKind::kFreeze);
  EXPECT_EQ(c.truth_faults[0].window.duration_s, 2.0);
  EXPECT_EQ(c.truth_faults[1].kind, TruthFaultKind::kTeleport);
  EXPECT_EQ(c.truth_faults[1].offset_enu_m, Vec3(1, -2, 3));
  EXPECT_EQ(c.truth_faults[2].kind, TruthFaultKind::kTimeJump);
  EXPECT_EQ(c.truth_faults[2].jump_s, -1.5);
  EXPECT_TRUE(load_run_config(write_temp("none.yaml", "scenario: {seed: 2}\n")).gnss_events.jamming.empty());
  EXPECT_FALSE(load_run_config(write_temp("none.yaml", "scenario: {seed: 2}\n")).control.has_value());
  const RunConfig ctl = load_run_config(write_temp("ctl.yaml", "control: {port: 7780}\n"));
  ASSERT_TRUE(ctl.control.has_value());
  EXPECT_EQ(ctl.control->port, 7780);
  EXPECT_EQ(ctl.control->address, "127.0.0.1") << "loopback by default";
  EXPECT_NE(load_error("control: {port: 70000}\n").find("control.port: 70000 outside [0, 65535]"), std::string::npos);
  EXPECT_NE(load_error("control: {socket: /tmp/x}\n").find("control.socket"), std::string::npos);

  const auto err = [](const std::string& entry) { return load_error("events:\n  - " + entry + "\n"); };
  const std::pair<const char*, const char*> cases[] = {
      {"{type: meaconing, duration_s: 1}", ":2: events[0].type: 'meaconing' is not an event type navemu knows (jamming, outage, antenna, satellite, spoofing, ionosphere, multipath, cable, reset, imu, truth)"},
      {"{duration_s: 1, j_over_s_db: 1}", "events[0].type: missing"},
      {"{type: jamming, j_over_s_db: 40}", "events[0].duration_s: missing"},
      {"{type: jamming, duration_s: 10}", "events[0].j_over_s_db: missing"},
      {"{type: jamming, duration_s: 10, ramp_s: 6, j_over_s_db: 40}", "events[0].ramp_s: ramp-in and ramp-out"},
      {"{type: jamming, duration_s: 10, j_over_s_db: 40, kind: pulsed}", "events[0].kind: 'pulsed' is not one of cw, matched, wideband"},
      {"{type: jamming, duration_s: 10, j_over_s_db: 40, band: E6}", "events[0].band: 'E6' is not one of L1, L2, L5"},
      {"{type: jamming, start_s: -1, duration_s: 10, j_over_s_db: 40}", "events[0].start_s"},
      {"{type: jamming, duration_s: 10, j_over_s_db: 40, power: 3}", "events[0].power"},
      {"{type: outage, duration_s: 10, ramp_s: 2}", "events[0].ramp_s"},
      {"{type: outage, duration_s: 10, azimuth_deg: [10]}", "events[0].azimuth_deg: must be [from, to]"},
      {"{type: outage, duration_s: 10, azimuth_deg: [10, 400]}", "events[0].azimuth_deg: must be [from, to]"},
      {"{type: antenna, duration_s: 10}", "events[0].fault: missing: open or short"},
      {"{type: antenna, duration_s: 10, fault: cut}", "events[0].fault: 'cut' is not one of open, short"},
      {"{type: satellite, duration_s: 10, clock_error_m: 5}", "events[0].prn: missing"},
      {"{type: satellite, duration_s: 10, prn: 33, clock_error_m: 5}", "events[0].prn: 33 outside [1, 32]"},
      {"{type: satellite, duration_s: 10, prn: 3}", "events[0].type: a satellite fault needs clock_error_m"},
      {"{type: satellite, duration_s: 10, prn: 3, orbit_error_m: [1, 2]}", "events[0].orbit_error_m: must be [radial"},
      {"{type: satellite, duration_s: 10, prn: 3, unhealthy: maybe}", "events[0].unhealthy"},
      {"{type: truth, duration_s: 1}", "events[0].fault: missing: freeze, teleport or time_jump"},
      {"{type: truth, duration_s: 1, fault: teleport}", "events[0].offset_m: must be [east, north, up]"},
      {"{type: truth, duration_s: 1, fault: time_jump}", "events[0].jump_s: missing"},
      {"{type: truth, duration_s: 1, fault: freeze, ramp_s: 0.2}", "events[0].ramp_s"},
      {"{type: reset, duration_s: 10}", "events[0].duration_s: a reset lasts as long as the receiver's start"},
      {"{type: reset, start: lukewarm}", "events[0].start: 'lukewarm' is not one of cold, hot, warm"},
      {"{type: reset, ramp_s: 1}", "events[0].ramp_s"},
      {"{type: cable}", "events[0].duration_s: missing"},
      {"{type: cable, duration_s: 3, ramp_s: 1}", "events[0].ramp_s"},
      {"{type: ionosphere, duration_s: 10}", "events[0].scale: missing: the true ionospheric delay's factor"},
      {"{type: ionosphere, duration_s: 10, scale: -1}", "events[0].scale"},
      {"{type: multipath, duration_s: 10, factor: 2}", "events[0].scale: missing: the multipath errors' factor"},
      {"{type: imu, duration_s: 10, sensor: gyro}", "events[0].fault: missing: bias, scale, noise, stuck, saturation, vibration, temperature, drop, duplicate, bus_off or error_frames"},
      {"{type: imu, duration_s: 10, fault: tilt}", "events[0].fault: 'tilt' is not one of"},
      {"{type: imu, duration_s: 10, fault: bias, bias_dps: 1}", "events[0].sensor: missing: gyro or accel"},
      {"{type: imu, duration_s: 10, fault: bias, sensor: gyro}", "events[0].bias_dps: missing"},
      {"{type: imu, duration_s: 10, fault: bias, sensor: gyro, bias_mps2: 1}", "events[0].bias_dps: missing"},
      {"{type: imu, duration_s: 10, fault: bias, sensor: accel, axis: w, bias_mps2: 1}", "events[0].axis: 'w' is not one of"},
      {"{type: imu, duration_s: 10, fault: noise, sensor: accel}", "events[0].noise_mps2_per_rthz: missing"},
      {"{type: imu, duration_s: 10, fault: stuck, sensor: accel, ramp_s: 1}", "events[0].ramp_s"},
      {"{type: imu, duration_s: 10, fault: drop, probability: 1.5}", "events[0].probability: must be at most 1"},
      {"{type: imu, duration_s: 10, fault: drop, sensor: gyro}", "events[0].sensor"},
      {"{type: imu, duration_s: 10, fault: duplicate, probability: 2}", "events[0].probability: must be at most 1"},
      {"{type: imu, duration_s: 10, fault: bus_off, ramp_s: 1}", "events[0].ramp_s"},
      {"{type: imu, duration_s: 10, fault: bus_off, sensor: gyro}", "events[0].sensor"},
      {"{type: imu, duration_s: 10, fault: error_frames, rate_hz: 0}", "events[0].rate_hz"},
      {"{type: imu, duration_s: 10, fault: saturation, sensor: accel}", "events[0].range_mps2: missing"},
      {"{type: imu, duration_s: 10, fault: saturation, sensor: gyro, range_dps: 0}", "events[0].range_dps"},
      {"{type: imu, duration_s: 10, ramp_s: 1, fault: saturation, sensor: gyro, range_dps: 9}", "events[0].ramp_s"},
      {"{type: imu, duration_s: 10, fault: vibration, sensor: gyro}", "events[0].type: a vibration needs amplitude_dps and frequency_hz"},
      {"{type: imu, duration_s: 10, fault: vibration, sensor: gyro, amplitude_dps: 1}", "events[0].frequency_hz: a sinusoid needs both"},
      {"{type: imu, duration_s: 10, fault: vibration, sensor: accel, frequency_hz: 3}", "events[0].amplitude_mps2: a sinusoid needs both"},
      {"{type: imu, duration_s: 10, fault: vibration, sensor: accel, psd_g2_per_hz: 0.1}", "events[0].band_hz: random vibration needs both"},
      {"{type: imu, duration_s: 10, fault: vibration, sensor: accel, psd_g2_per_hz: 0.1, band_hz: [50, 20]}", "events[0].band_hz: must be [low, high]"},
      {"{type: imu, duration_s: 10, fault: vibration, sensor: accel, psd_dps2_per_hz: 0.1, band_hz: [5, 20]}", "events[0].psd_g2_per_hz: random vibration needs both"},
      {"{type: imu, duration_s: 10, fault: temperature}", "events[0].temperature_c: missing"},
      {"{type: imu, duration_s: 10, fault: temperature, temperature_c: 5, sensor: gyro}", "events[0].sensor"},
      {"{type: outage, duration_s: 10, at: '2394:1', start_s: 4}", "events[0].at: give either at (a GPS time) or start_s"},
      {"{type: outage, duration_s: 10, at: yesterday}", "events[0].at: 'yesterday' is not a time"},
      {"{type: spoofing, duration_s: 10}", "events[0].offset_m: missing"},
      {"{type: spoofing, duration_s: 10, offset_m: [1, 2]}", "events[0].offset_m: must be [east, north, up]"},
      {"{type: spoofing, duration_s: 10, offset_m: [1, 2, 3], power_advantage_db: -3}", "events[0].power_advantage_db"},
  };
  for (const auto& [entry, expected] : cases)
    EXPECT_NE(err(entry).find(expected), std::string::npos) << entry << " -> " << err(entry);
}

// Each GNSS output stands for one of the receiver's ports: `port:` on pty, serial and file,
// `receiver_port:` on tcp and udp (where `port` is the network port); UART1 when not given.
TEST(RunConfig, GnssOutputsNameTheReceiverPortTheyStandFor) {
  const RunConfig c = load_run_config(write_temp(
      "ports.yaml",
      "gnss:\n  profile: ublox-f9p\n  outputs:\n    - {type: pty, link: /tmp/x-usb, port: usb}\n"
      "    - {type: tcp, port: 5000, receiver_port: uart2}\n    - {type: file, path: /tmp/x.ubx}\n"));
  ASSERT_EQ(c.gnss_outputs.size(), 3u);
  EXPECT_EQ(c.gnss_outputs[0].receiver_port, "usb");
  EXPECT_EQ(c.gnss_outputs[1].receiver_port, "uart2");
  EXPECT_EQ(c.gnss_outputs[2].receiver_port, "uart1");
  const std::string e = load_error("gnss:\n  outputs:\n    - {type: pty, port: usb3}\n");
  EXPECT_NE(e.find(":3: gnss.outputs[0].port: 'usb3' is not one of i2c, uart1, uart2, usb, spi"), std::string::npos)
      << e;
}

TEST(RunConfig, EveryShippedGnssProfileLoads) {
  const auto names = available_gnss_profiles();
  ASSERT_GE(names.size(), 2u);
  for (const std::string& n : names) {
    const GnssProfile p = load_gnss_profile(n);
    EXPECT_FALSE(p.sentences.empty()) << n;
    EXPECT_GT(p.rate_hz, 0.0) << n;
  }
  const GnssProfile g = load_gnss_profile("garmin-18x-5hz");
  ASSERT_EQ(g.sentences.size(), 5u);
  EXPECT_EQ(g.sentences[0].first, "RMC");
  EXPECT_EQ(g.sentences[3], (std::pair<std::string, int>{"GSV", 5}));
  EXPECT_EQ(g.style, "garmin");
}

TEST(RunConfig, ProfileAntennaPattern) {
  const GnssProfile g = load_gnss_profile("garmin-18x-5hz");
  ASSERT_EQ(g.antenna_gain_db_by_el_deg.size(), 10u);
  EXPECT_EQ(g.antenna_gain_db_by_el_deg.front(), (std::pair<double, double>{-90.0, -20.0}));
  EXPECT_EQ(g.antenna_gain_db_by_el_deg.back(), (std::pair<double, double>{90.0, 0.0}));
  EXPECT_EQ(g.antenna_lhcp_rejection_db, 15.0);
  const auto bad = [](const std::string& antenna) {
    try {
      load_gnss_profile(write_temp("ant.yaml", "sentences: {RMC: 1}\nantenna:\n" + antenna).string());
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(bad("  gain_db_by_el_deg: [[10, -8], [5, -10]]\n").find(":3: antenna.gain_db_by_el_deg: elevations must rise"),
            std::string::npos)
      << bad("  gain_db_by_el_deg: [[10, -8], [5, -10]]\n");
  EXPECT_NE(bad("  gain_db_by_el_deg: [[10, -8, 1]]\n").find("expected a list of [number, number] pairs"),
            std::string::npos);
  EXPECT_NE(bad("  gain_db_by_el_deg: [[10, x]]\n").find("'x' is not a number"), std::string::npos);
}

// `systems`: what the receiver tracks; the main NMEA talker follows unless given.
TEST(RunConfig, ProfileSystemsAndTheirTalker) {
  const auto load = [](const std::string& yaml) {
    return load_gnss_profile(write_temp("sys.yaml", "sentences: {RMC: 1}\n" + yaml).string());
  };
  EXPECT_EQ(load("").systems, system_bit(GnssSystem::kGps));
  EXPECT_EQ(load("").talker, "GP");
  const GnssProfile four = load("systems: [GPS, GLONASS, Galileo, BeiDou]\n");
  EXPECT_EQ(four.systems, system_bit(GnssSystem::kGps) | system_bit(GnssSystem::kGlonass) |
                              system_bit(GnssSystem::kGalileo) | system_bit(GnssSystem::kBeidou));
  EXPECT_EQ(four.talker, "GN");
  EXPECT_EQ(load("systems: [Galileo]\n").talker, "GA");
  EXPECT_EQ(load("systems: [GLONASS, GPS]\ntalker: GP\n").talker, "GP");
  const auto bad = [&](const std::string& yaml) {
    try {
      load(yaml);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(bad("systems: [GPS, Compass]\n").find(":2: systems: unknown system 'Compass'"), std::string::npos)
      << bad("systems: [GPS, Compass]\n");
  EXPECT_NE(bad("systems: []\n").find("systems: at least one system"), std::string::npos)
      << bad("systems: []\n");
  // `bands`: the front ends; L1 alone by default, L1 always.
  EXPECT_EQ(load("").bands, band_bit(Band::kL1));
  EXPECT_EQ(load("bands: [L1, L5]\n").bands, band_bit(Band::kL1) | band_bit(Band::kL5));
  EXPECT_NE(bad("bands: [L1, E6]\n").find(":2: bands: unknown band 'E6': L1, L2 or L5"), std::string::npos)
      << bad("bands: [L1, E6]\n");
  EXPECT_NE(bad("bands: [L2]\n").find(":2: bands: L1 is needed"), std::string::npos) << bad("bands: [L2]\n");
}

TEST(RunConfig, UnknownKeyIsReportedWithItsLine) {
  const std::string e = load_error("scenario:\n  seed: 3\n  sede: 4\n");
  EXPECT_NE(e.find("bad.yaml:3: scenario.sede: unknown key"), std::string::npos) << e;
}

TEST(RunConfig, BadValuesNameTheKey) {
  EXPECT_NE(load_error("truth:\n  source: teleport\n").find("truth.source: 'teleport' is not one of"),
            std::string::npos);
  EXPECT_NE(load_error("truth:\n  circle: {radius_m: -3}\n").find(":2: truth.circle.radius_m: must be positive"),
            std::string::npos)
      << load_error("truth:\n  circle: {radius_m: -3}\n");
  EXPECT_NE(load_error("truth:\n  position: {lat_deg: 95}\n").find("truth.position.lat_deg"),
            std::string::npos);
  EXPECT_NE(load_error("scenario:\n  seed: abc\n").find("scenario.seed: 'abc' is not an integer"),
            std::string::npos);
  EXPECT_NE(load_error("gnss:\n  profile: nosuch\n").find("no such GNSS profile (available: "),
            std::string::npos);
  EXPECT_NE(load_error("gnss:\n  outputs:\n    - {type: serial}\n").find("gnss.outputs[0].device: required"),
            std::string::npos)
      << load_error("gnss:\n  outputs:\n    - {type: serial}\n");
  EXPECT_NE(load_error("scenario:\n  time: lockstep\n").find("needs truth.source udp"),
            std::string::npos);
  EXPECT_NE(load_error("truth:\n  source: waypoints\n").find("at least two waypoints"),
            std::string::npos);
  EXPECT_NE(load_error("scenario: [1, 2\n").find("YAML syntax error"), std::string::npos);
}

TEST(RunConfig, RelativePathsAreRelativeToTheFile) {
  const auto p = write_temp("rel.yaml", "truth:\n  source: csv\n  csv: {path: track.csv}\n");
  const RunConfig c = load_run_config(p);
  EXPECT_EQ(c.truth.csv_path, (p.parent_path() / "track.csv").string());
}

TEST(RunConfig, MissingFileIsAnInputError) {
  EXPECT_THROW(load_run_config("/nonexistent/navemu.yaml"), InputError);
}

}  // namespace
}  // namespace navemu
