#pragma once
// Checking captured CAN traffic against navemu's own IMU log: candump -L files (written by
// navemu simulate, by can-utils' candump, or by python-can's logger) are parsed here, every
// frame is decoded (J1939 by its published scaling, independently of navemu's encoder; the
// high-resolution layout by its decoder, whose CRC check makes it independent of the byte
// layout guessed here) and compared with the imu.csv / imu.log row of the same sample.
//
// A reader that falls behind loses frames at its own socket, not at the sender: candump -d
// reports them with a line "DROPCOUNT: dropped N CAN frames on 'vcan0' socket (total drops T)"
// before the first frame it received after them (can-utils candump.c, SO_RXQ_OVFL: the count
// the kernel stamps on each queued frame). Such a line marks a hole in the log; the samples at
// its edges are incomplete, and the check dates what is left of them or counts them as cut.

#include <gtest/gtest.h>

#include <array>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "protocols/can_frames.hpp"
#include "tests/test_support.hpp"

namespace navemu::test {

struct LoggedFrame {
  double t_s = 0.0;  // the log's time stamp
  std::uint32_t id = 0;
  bool extended = false;
  bool fd = false;
  std::vector<std::uint8_t> data;
  // Frames the reader's socket dropped just before this one (a DROPCOUNT line before it), and
  // just after it with no frame logged after them (the end of a recording: tests/vcan).
  std::uint64_t dropped_before = 0, dropped_after = 0;
};

// "DROPCOUNT: dropped 12 CAN frames on 'vcan0' socket (total drops 40)" -> 12.
inline std::optional<std::uint64_t> parse_candump_dropcount(const std::string& line) {
  unsigned long long n = 0;
  if (std::sscanf(line.c_str(), "DROPCOUNT: dropped %llu CAN frame", &n) != 1) return std::nullopt;
  return n;
}

// "(1700000000.123456) vcan0 18F02A80#0011223344556677" or "... 510##1<hex>".
inline std::optional<LoggedFrame> parse_candump_line(const std::string& line) {
  LoggedFrame f;
  std::istringstream ss(line);
  std::string stamp, iface, frame;
  if (!(ss >> stamp >> iface >> frame) || stamp.size() < 3 || stamp.front() != '(') return std::nullopt;
  f.t_s = std::stod(stamp.substr(1, stamp.size() - 2));
  const std::size_t hash = frame.find('#');
  if (hash == std::string::npos || (hash != 3 && hash != 8)) return std::nullopt;
  f.id = static_cast<std::uint32_t>(std::stoul(frame.substr(0, hash), nullptr, 16));
  f.extended = hash == 8;
  std::size_t pos = hash + 1;
  if (pos < frame.size() && frame[pos] == '#') {
    f.fd = true;
    pos += 2;  // '#' and the flags nibble
  }
  const std::string hex = frame.substr(std::min(pos, frame.size()));
  if (hex.size() % 2 != 0) return std::nullopt;
  for (std::size_t i = 0; i < hex.size(); i += 2)
    f.data.push_back(static_cast<std::uint8_t>(std::stoul(hex.substr(i, 2), nullptr, 16)));
  return f;
}

// The frames of a candump log, each with the reader's drops before it (candump -d).
inline std::vector<LoggedFrame> read_candump_log(const std::filesystem::path& p) {
  std::vector<LoggedFrame> frames;
  std::ifstream in(p);
  std::uint64_t dropped = 0;
  for (std::string line; std::getline(in, line);) {
    if (auto n = parse_candump_dropcount(line)) {
      dropped += *n;
    } else if (auto f = parse_candump_line(line)) {
      f->dropped_before = std::exchange(dropped, 0);
      frames.push_back(*f);
    }
  }
  if (!frames.empty()) frames.back().dropped_after = dropped;  // candump never ends on one
  return frames;
}

// Frames the reader's socket dropped over the whole log.
inline std::uint64_t reader_dropped(const std::vector<LoggedFrame>& frames) {
  std::uint64_t n = 0;
  for (const LoggedFrame& f : frames) n += f.dropped_before + f.dropped_after;
  return n;
}

// One row of imu.csv (navemu simulate) or of imu.log (navemu run, imu.log).
struct ImuRow {
  std::array<double, 3> f_mps2{}, w_radps{};
  bool truth_valid = true;
  std::int64_t gps_time_ns = 0;
  int sequence = 0;
};

inline std::vector<ImuRow> read_imu_rows(const std::filesystem::path& p) {
  std::vector<ImuRow> rows;
  const CsvTable t(p);
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t.row(i).size() < t.header().size()) continue;  // a row cut short (the log still open)
    ImuRow r;
    for (std::size_t k = 0; k < 3; ++k) {
      const char axis[] = {static_cast<char>('x' + k), '\0'};
      r.f_mps2[k] = t.num(i, std::string("f_") + axis + "_mps2");
      r.w_radps[k] = t.num(i, std::string("w_") + axis + "_radps");
    }
    r.truth_valid = t(i, "truth_valid") == "1";
    r.gps_time_ns = t.integer(i, "gps_time_ns");
    r.sequence = static_cast<int>(t.integer(i, "sequence"));
    rows.push_back(r);
  }
  return rows;
}

// SAE J1939-71 decoding by the published scaling (little-endian 16-bit values):
// ARI (PGN 61482) bytes 1-2 pitch, 3-4 roll, 5-6 yaw rate, 1/128 deg/s, offset -250 deg/s;
// ACCS (PGN 61485) bytes 1-2 lateral, 3-4 longitudinal, 5-6 vertical, 0.01 m/s^2, offset -320.
inline std::uint32_t j1939_pgn(std::uint32_t id) { return (id >> 8) & 0x3FFFF; }
inline double j1939_u16(const std::vector<std::uint8_t>& d, std::size_t byte, double lsb, double offset) {
  return (d[byte] | (d[byte + 1] << 8)) * lsb + offset;
}

struct CanCheck {
  // Samples checked against their row, per layout (ARI and ACCS frames; classic high-resolution
  // samples and CAN FD frames that decode).
  std::size_t ari = 0, accs = 0, highres = 0, highres_fd = 0;
  std::size_t samples = 0;     // samples (groups of frames) seen
  std::size_t cut = 0;         // samples at a hole not checked in full (see check_frames_against_log)
  std::size_t mismatches = 0;  // frames whose values differ from the log beyond resolution
  double max_rate_err_radps = 0, max_accel_err_mps2 = 0;  // J1939
  double max_hr_rate_err_radps = 0, max_hr_accel_err_mps2 = 0;  // high resolution
  std::int64_t first_time_ns = 0, last_time_ns = 0;  // of the first and last checked sample's row
  // Each checked sample's row time and the log's time stamp of its first frame, by row time.
  std::map<std::int64_t, double> arrival_s;
  std::string first_problem;
};

// Groups the frames into samples (a sample starts at an ARI frame, or at a high-resolution
// TIME or FD frame that does not follow an ARI of the same sample), finds each sample's row
// and compares every value with it. The row: by the high-resolution GPS time when the sample
// has one; otherwise the row after the previous sample's (the first sample's: `first_row`).
// A hole in the log (frames the reader dropped, LoggedFrame::dropped_*) ends the sample before
// it and starts a new one after it. Those two samples may be incomplete: a classic
// high-resolution sample there that does not decode, and J1939 frames after a hole in samples
// without a high-resolution time until one with it (nothing dates them), are counted as `cut`,
// not as problems.
inline CanCheck check_frames_against_log(const std::vector<LoggedFrame>& frames,
                                         const std::vector<ImuRow>& rows,
                                         std::size_t first_row = 0,
                                         const can::highres::Config& hr = {}) {
  CanCheck c;
  constexpr double kDeg = 3.14159265358979323846 / 180.0;
  const auto problem = [&](const std::string& what) {
    ++c.mismatches;
    if (c.first_problem.empty()) c.first_problem = what;
  };
  const auto to_can = [](const LoggedFrame& f) {
    can::CanFrame cf;
    cf.id = f.id;
    cf.extended = f.extended;
    cf.fd = f.fd;
    cf.len = static_cast<std::uint8_t>(std::min<std::size_t>(f.data.size(), 64));
    std::copy_n(f.data.begin(), cf.len, cf.data.begin());
    return cf;
  };
  const auto is_j1939 = [](const LoggedFrame& f, std::uint32_t pgn) {
    return f.extended && f.data.size() == 8 && j1939_pgn(f.id) == pgn;
  };

  // 1. Samples.
  struct Sample {
    double t_s = 0;  // of its first frame
    bool hole_before = false, hole_after = false;
    std::vector<const LoggedFrame*> j1939;
    std::vector<can::CanFrame> classic;
    std::optional<can::CanFrame> fd;
  };
  std::vector<Sample> samples;
  bool open_j1939 = false;  // the current sample has J1939 frames and no high-resolution one yet
  bool hole = false;        // a hole lies before the current frame
  const auto start_sample = [&](const LoggedFrame& f) {
    samples.emplace_back();
    samples.back().t_s = f.t_s;
    samples.back().hole_before = hole;
    hole = false;
  };
  for (const LoggedFrame& f : frames) {
    if (f.dropped_before > 0) {
      if (!samples.empty()) samples.back().hole_after = true;
      hole = true;
      open_j1939 = false;
    }
    if (is_j1939(f, can::j1939::kPgnAri)) {
      start_sample(f);
      samples.back().j1939.push_back(&f);
      open_j1939 = true;
    } else if (is_j1939(f, can::j1939::kPgnAccs)) {
      if (samples.empty() || hole) {
        start_sample(f);
        open_j1939 = true;
      }
      samples.back().j1939.push_back(&f);
    } else {
      const std::uint32_t offset = f.id - hr.base_id;
      const bool ours = f.extended == hr.extended && f.id >= hr.base_id &&
                        (offset <= can::highres::kOffsetStatus || offset == can::highres::kOffsetFd);
      if (!ours) {
        problem("unexpected frame id " + std::to_string(f.id));
        continue;
      }
      const bool starts = offset == can::highres::kOffsetTime || offset == can::highres::kOffsetFd;
      const bool joins = open_j1939 || (offset == can::highres::kOffsetFd && !samples.empty() &&
                                        !samples.back().classic.empty() && !samples.back().fd);
      if (samples.empty() || hole || (starts && !joins)) start_sample(f);
      if (offset == can::highres::kOffsetFd) {
        samples.back().fd = to_can(f);
      } else {
        samples.back().classic.push_back(to_can(f));
      }
      open_j1939 = false;
    }
    if (f.dropped_after > 0) samples.back().hole_after = true;
  }
  c.samples = samples.size();

  // 2. Rows and values.
  std::map<std::int64_t, std::size_t> row_of_time;
  for (std::size_t i = 0; i < rows.size(); ++i) row_of_time[rows[i].gps_time_ns] = i;
  std::optional<std::size_t> next_row = first_row;  // of a sample without a high-resolution time
  bool lost_at_hole = false;  // no next_row since a hole: J1939 samples until a dated one are cut
  bool checked_any = false;
  for (const Sample& s : samples) {
    const bool at_hole = s.hole_before || s.hole_after;
    bool cut = false;
    std::vector<can::highres::Decoded> hr_values;
    if (!s.classic.empty()) {
      if (auto d = can::highres::decode_classic(s.classic, hr)) {
        ++c.highres;
        hr_values.push_back(*d);
      } else if (at_hole) {
        cut = true;
      } else {
        problem("classic high-resolution sample does not decode (CRC, ids, order or length)");
      }
    }
    if (s.fd) {
      if (auto d = can::highres::decode_fd(*s.fd, hr)) {
        ++c.highres_fd;
        hr_values.push_back(*d);
      } else {
        problem("CAN FD high-resolution sample does not decode");
      }
    }
    if (cut) ++c.cut;
    std::optional<std::size_t> row;
    if (!hr_values.empty()) {
      const auto it = row_of_time.find(hr_values.front().gps_time_ns);
      if (it == row_of_time.end()) {
        problem("sample at GPS time " + std::to_string(hr_values.front().gps_time_ns) + " not in the log");
        next_row.reset();
        continue;
      }
      row = it->second;
    } else if (s.j1939.empty()) {
      next_row.reset();  // nothing of this sample can be checked; it was counted above
      lost_at_hole = lost_at_hole || at_hole;
      continue;
    } else if (s.hole_before || (!next_row && lost_at_hole)) {
      if (!cut) ++c.cut;
      next_row.reset();
      lost_at_hole = true;
      continue;
    } else if (!next_row) {
      problem("J1939 sample that nothing dates (the sample before it was not found)");
      continue;
    } else if (*next_row >= rows.size()) {
      problem("more samples than log rows");
      continue;
    } else {
      row = next_row;
    }
    next_row = *row + 1;
    lost_at_hole = false;
    const ImuRow& r = rows[*row];
    if (!checked_any) c.first_time_ns = r.gps_time_ns;
    checked_any = true;
    c.last_time_ns = r.gps_time_ns;
    c.arrival_s.emplace(r.gps_time_ns, s.t_s);  // a sample split by a hole: its first part
    for (const can::highres::Decoded& d : hr_values) {
      if (d.gps_time_ns != r.gps_time_ns) problem("the sample's two high-resolution times differ");
      if (d.sequence != static_cast<std::uint16_t>(r.sequence)) problem("sequence differs");
      if (((d.flags & can::highres::kFlagTruthLost) != 0) == r.truth_valid) problem("truth-lost flag differs");
      for (std::size_t i = 0; i < 3; ++i) {
        const double ew = std::abs(d.w_body_radps[i] - r.w_radps[i]);
        const double ef = std::abs(d.f_body_mps2[i] - r.f_mps2[i]);
        c.max_hr_rate_err_radps = std::max(c.max_hr_rate_err_radps, ew);
        c.max_hr_accel_err_mps2 = std::max(c.max_hr_accel_err_mps2, ef);
        // Full precision: half a wire LSB, plus the log's 9 significant digits.
        if (ew > 0.5e-7 + 1e-8 * std::abs(r.w_radps[i]) || ef > 0.5e-6 + 1e-8 * std::abs(r.f_mps2[i]))
          problem("high-resolution value differs from the log");
      }
    }
    for (const LoggedFrame* f : s.j1939) {
      if (is_j1939(*f, can::j1939::kPgnAri)) {
        ++c.ari;
        const double lsb = 1.0 / 128.0;
        const std::array<double, 3> got{j1939_u16(f->data, 2, lsb, -250) * kDeg,   // roll = w_x
                                        j1939_u16(f->data, 0, lsb, -250) * kDeg,   // pitch = w_y
                                        j1939_u16(f->data, 4, lsb, -250) * kDeg};  // yaw = w_z
        for (std::size_t i = 0; i < 3; ++i) {
          const double e = std::abs(got[i] - r.w_radps[i]);
          c.max_rate_err_radps = std::max(c.max_rate_err_radps, e);
          if (e > 0.5 * lsb * kDeg + 1e-9) problem("ARI rate differs from the log beyond 1/256 deg/s");
        }
      } else {
        ++c.accs;
        const std::array<double, 3> got{j1939_u16(f->data, 2, 0.01, -320),    // longitudinal = f_x
                                        j1939_u16(f->data, 0, 0.01, -320),    // lateral = f_y
                                        -j1939_u16(f->data, 4, 0.01, -320)};  // vertical = -f_z
        for (std::size_t i = 0; i < 3; ++i) {
          const double e = std::abs(got[i] - r.f_mps2[i]);
          c.max_accel_err_mps2 = std::max(c.max_accel_err_mps2, e);
          if (e > 0.005 + 1e-9) problem("ACCS acceleration differs from the log beyond 0.005 m/s^2");
        }
      }
    }
  }
  return c;
}

}  // namespace navemu::test
