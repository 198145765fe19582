#pragma once
// The platform header PX4-GPSDrivers asks of its host (its README: "definitions.h must include
// definitions for sensor_gnss_relative_s, sensor_gps_s and satellite_info_s"), written for
// navemu's harness (navemu_px4_gps.cpp) from what src/ubx.cpp, gps_helper.cpp, rtcm.cpp and
// crc.cpp use; the driver includes it through -DGPS_DEFINITIONS_HEADER='"definitions.h"'
// (../shared/TESTING.md, "PX4's u-blox driver").
//
// Only the members the u-blox driver reads or writes are here. Their types follow the UBX
// fields they are filled from (u-blox 8 / M8 Receiver Description UBX-13003221 and ZED-F9P
// Interface Description UBX-18010854): e.g. noise_per_ms holds MON-HW/MON-RF noisePerMS (U2),
// jamming_indicator holds jamInd (U1), elevation and azimuth are the bytes the driver stores
// (it casts NAV-SAT elev to uint8 and scales azim to 0..255).

#include <cmath>
#include <cstdint>
#include <ctime>
#include <time.h>  // timespec, clock_gettime, mktime (POSIX)

// Monotonic microseconds: the driver's timeouts (waitForAck, receive) and report time stamps.
using gps_abstime = std::uint64_t;

inline gps_abstime gps_absolute_time() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<gps_abstime>(ts.tv_sec) * 1'000'000u +
         static_cast<gps_abstime>(ts.tv_nsec) / 1'000u;
}

// NAV-PVT headMot / headAcc (1e-5 deg) to radians.
#ifndef M_DEG_TO_RAD_F
#define M_DEG_TO_RAD_F 0.0174532925f
#endif

// The driver's messages (firmware and protocol version, module, warnings): the harness prints
// each as a report line; `level` is 'I', 'W' or 'E'.
void navemu_px4_log(char level, const char* format, ...) __attribute__((format(printf, 2, 3)));
#define GPS_INFO(...) navemu_px4_log('I', __VA_ARGS__)
#define GPS_WARN(...) navemu_px4_log('W', __VA_ARGS__)
#define GPS_ERR(...) navemu_px4_log('E', __VA_ARGS__)

// One position/velocity report (filled from NAV-PVT, or NAV-POSLLH/SOL/VELNED/TIMEUTC on parts
// without NAV-PVT; NAV-DOP, NAV-STATUS, NAV-HPPOSLLH, MON-HW or MON-RF, RXM-RTCM add to it).
struct sensor_gps_s {
  gps_abstime timestamp = 0;          // gps_absolute_time() of the latest NAV-PVT/POSLLH
  std::uint64_t time_utc_usec = 0;    // UTC of the solution, microseconds since 1970
  std::int32_t timestamp_time_relative = 0;
  double latitude_deg = 0, longitude_deg = 0;
  double altitude_msl_m = 0, altitude_ellipsoid_m = 0;
  float eph = 0, epv = 0;             // hAcc, vAcc (m)
  float hdop = 0, vdop = 0;
  float s_variance_m_s = 0;           // sAcc (m/s)
  float c_variance_rad = 0;           // headAcc (rad)
  float vel_m_s = 0, vel_n_m_s = 0, vel_e_m_s = 0, vel_d_m_s = 0;
  float cog_rad = 0;
  float heading = NAN, heading_accuracy = NAN;  // NAV-RELPOSNED (moving base)
  std::uint8_t fix_type = 0;          // 0 none, 2 2D, 3 3D, 4 DGNSS, 5 RTK float, 6 RTK fixed
  std::uint8_t satellites_used = 0;
  bool vel_ned_valid = false;
  std::int32_t noise_per_ms = 0;      // MON-HW/MON-RF noisePerMS
  std::uint16_t automatic_gain_control = 0;  // MON-HW agcCnt
  std::int32_t jamming_indicator = 0; // MON-HW/MON-RF jamInd (0..255)
  std::uint8_t jamming_state = 0;     // MON-RF flags (jammingState)
  std::uint8_t spoofing_state = 0;    // NAV-STATUS flags2 spoofDetState
  bool rtcm_crc_failed = false;       // RXM-RTCM
  std::uint8_t rtcm_msg_used = 0;
};

// The sky: one entry per NAV-SAT (or NAV-SVINFO) satellite, at most SAT_INFO_MAX_SATELLITES.
struct satellite_info_s {
  static constexpr std::uint8_t SAT_INFO_MAX_SATELLITES = 40;
  gps_abstime timestamp = 0;
  std::uint8_t count = 0;
  std::uint8_t svid[SAT_INFO_MAX_SATELLITES] = {};  // NAV-SVINFO numbering
  std::uint8_t used[SAT_INFO_MAX_SATELLITES] = {};
  std::uint8_t elevation[SAT_INFO_MAX_SATELLITES] = {};  // deg, the I1 stored as a byte
  std::uint8_t azimuth[SAT_INFO_MAX_SATELLITES] = {};    // 0..255 for 0..360 deg
  std::uint8_t snr[SAT_INFO_MAX_SATELLITES] = {};        // C/N0, dBHz
  std::uint8_t prn[SAT_INFO_MAX_SATELLITES] = {};
};

// NAV-RELPOSNED, handed to the host through the gotRelativePositionMessage callback.
struct sensor_gnss_relative_s {
  gps_abstime timestamp_sample = 0;
  std::uint64_t time_utc_usec = 0;
  std::uint16_t reference_station_id = 0;
  float position[3] = {};           // N, E, D (m)
  float position_length = 0;
  float heading = NAN, heading_accuracy = NAN;
  float position_accuracy[3] = {};
  float accuracy_length = 0;
  bool gnss_fix_ok = false, differential_solution = false, relative_position_valid = false;
  bool carrier_solution_floating = false, carrier_solution_fixed = false;
  bool moving_base_mode = false, reference_position_miss = false;
  bool reference_observations_miss = false, heading_valid = false;
  bool relative_position_normalized = false;
};
