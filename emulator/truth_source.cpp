#include "emulator/truth_source.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>

#include "emulator/truth_csv.hpp"
#include "core/errors.hpp"
#include "models/trajectory.hpp"
#include "transports/byte_port.hpp"

namespace navemu {

namespace {


class GeneratorSource final : public TruthSource {
 public:
  GeneratorSource(std::unique_ptr<Trajectory> t, std::string what)
      : traj_(std::move(t)), what_(std::move(what)) {}
  std::optional<ImuTruth> at(GpsTime t) override { return traj_->at(t); }
  std::string describe() const override { return what_; }

 private:
  std::unique_ptr<Trajectory> traj_;
  std::string what_;
};

// `stream`: the time rules of streamed truth apply (a file's rows are checked when read).
TruthStreamLimits stream_limits(const TruthSpec& spec, double timeout_s, bool stream) {
  TruthStreamLimits l;
  l.timeout_s = timeout_s;
  if (stream) l.max_jump_s = spec.max_jump_s;
  l.resync_samples = spec.resync_samples;
  return l;
}

// "8 loops", or "forever" for 0 (models/trajectory.hpp).
std::string count_or_forever(int n, const char* what) {
  return n == 0 ? std::string("forever") : fmt::format("{} {}", n, what);
}

// "3600.000 s ahead of the scenario clock", "12.500 s back from the newest sample"
std::string describe_jump(const TruthResync& r) {
  const double jump_s = static_cast<double>(r.jump_ns) * 1e-9;
  return fmt::format("{:.3f} s {} {}", std::abs(jump_s), jump_s >= 0 ? "ahead of" : "behind",
                     r.against_clock ? "the scenario clock" : "the newest accepted sample");
}

// A truth CSV (or standard input) replayed from the scenario start: row time_s maps to
// start + (time_s - first row's time_s). Rows are read ahead into a buffer as queries need.
// A file's times must increase (an InputError names the row otherwise); standard input is a
// stream, whose times out of order follow the streamed-truth rules (duplicate, backwards,
// future, resync), the first few refused rows named by line.
class CsvSource final : public TruthSource {
 public:
  static constexpr int kRowsNamed = 10;  // refused rows reported by line; later ones counted

  CsvSource(const TruthSpec& spec, GpsTime start)
      : reader_(spec.csv_path == "-" ? "/dev/stdin" : spec.csv_path, spec.csv_path != "-"),
        start_(start),
        buffer_(stream_limits(spec, 0.0, spec.csv_path == "-")),
        resync_samples_(spec.resync_samples) {}

  std::optional<ImuTruth> at(GpsTime t) override {
    TruthRow row;
    while (!end_ && (!buffer_.newest_time() || *buffer_.newest_time() < t)) {
      if (!reader_.next(row)) {
        end_ = true;
        break;
      }
      if (!first_s_) first_s_ = row.time_s;
      ImuTruth s;
      s.t = start_.plus_s(row.time_s - *first_s_);
      s.position = row.position;
      s.v_ned_mps = row.v_ned_mps;
      s.q_ned_from_body = quat_from_euler_rpy(row.rpy_rad);
      s.f_body_mps2 = row.f_body_mps2;
      s.w_ib_body_radps = row.w_ib_body_radps;
      s.temperature_c = row.temperature_c;
      note(buffer_.push(s), row.time_s);
    }
    return buffer_.at(t);
  }
  std::optional<GpsTime> newest() const override { return buffer_.newest_time(); }
  const TruthCounters* counters() const override { return &buffer_.counters(); }
  std::optional<std::string> take_warning() override {
    if (warnings_.empty()) return std::nullopt;
    std::string w = std::move(warnings_.front());
    warnings_.erase(warnings_.begin());
    return w;
  }
  std::string describe() const override { return "truth CSV " + reader_.path(); }

 private:
  void note(TruthVerdict v, double time_s) {
    const std::string where = fmt::format("truth CSV {}:{}: time_s {}", reader_.path(), reader_.line(), time_s);
    if (v == TruthVerdict::kResync) {
      warnings_.push_back(fmt::format(
          "{}: the rows' time jumped {}; re-synchronised after {} consecutive rows: from here on "
          "a row's time maps to scenario time {:+.3f} s",
          where, describe_jump(*buffer_.last_resync()), resync_samples_,
          static_cast<double>(buffer_.last_resync()->offset_ns) * 1e-9));
    } else if (v != TruthVerdict::kAccepted && named_++ < kRowsNamed) {
      warnings_.push_back(fmt::format("{}: row refused ({}){}", where, to_string(v),
                                      named_ == kRowsNamed ? "; further refused rows are only counted" : ""));
    }
  }
  TruthCsvReader reader_;
  GpsTime start_;
  TruthBuffer buffer_;
  int resync_samples_;
  std::optional<double> first_s_;
  bool end_ = false;
  int named_ = 0;
  std::vector<std::string> warnings_;
};

class UdpSource final : public TruthSource {
 public:
  UdpSource(const TruthSpec& spec, GpsTime host_offset)
      : rx_(spec.udp_address, spec.udp_port),
        host_offset_(host_offset),
        buffer_(stream_limits(spec, spec.timeout_s, true)),
        resync_samples_(spec.resync_samples) {}

  void poll(std::optional<GpsTime> clock) override {
    truth_datagram::Message m;
    for (int n = 0; n < 1000; ++n) {  // bounded: a flood cannot hold the loop
      const std::size_t len = rx_.receive(buf_);
      if (len == 0) break;
      if (truth_datagram::decode(std::span<const std::uint8_t>(buf_.data(), len), m) !=
          truth_datagram::DecodeResult::kOk) {
        ++buffer_.counters().bad_framing;
        continue;
      }
      const std::optional<ImuTruth> s = truth_from_message(m, host_offset_);
      if (!s) {
        ++buffer_.counters().not_finite;
        continue;
      }
      if (buffer_.push(*s, clock) == TruthVerdict::kResync) resync_pending_ = true;
    }
    buffer_.counters().lost = rx_.kernel_dropped();
  }
  std::optional<ImuTruth> at(GpsTime t) override { return buffer_.at(t); }
  std::optional<GpsTime> newest() const override { return buffer_.newest_time(); }
  const TruthCounters* counters() const override { return &buffer_.counters(); }
  std::optional<std::string> take_warning() override {
    if (!resync_pending_) return std::nullopt;
    resync_pending_ = false;
    const TruthResync& r = *buffer_.last_resync();
    return fmt::format(
        "truth datagrams on udp port {}: the stream's time jumped {}; re-synchronised after {} "
        "consistent datagrams: their time stamps now map to scenario time {:+.3f} s",
        rx_.port(), describe_jump(r), resync_samples_, static_cast<double>(r.offset_ns) * 1e-9);
  }
  std::string describe() const override {
    return fmt::format("truth datagrams on udp port {}", rx_.port());
  }
  int port() const { return rx_.port(); }

 private:
  transport::UdpReceiver rx_;
  GpsTime host_offset_;
  TruthBuffer buffer_;
  int resync_samples_;
  bool resync_pending_ = false;
  std::array<std::uint8_t, 8192> buf_{};
};

}  // namespace

std::optional<ImuTruth> truth_from_message(const truth_datagram::Message& m, GpsTime host_offset) {
  using namespace truth_datagram;
  const auto finite = [](const auto& a) {
    for (double x : a)
      if (!std::isfinite(x)) return false;
    return true;
  };
  if (!finite(m.position) || !finite(m.velocity_mps) || !finite(m.attitude) ||
      (m.has_rates && (!finite(m.f_body_mps2) || !finite(m.w_body_radps))) ||
      (m.has_temperature && !std::isfinite(m.temperature_c)))
    return std::nullopt;
  ImuTruth s;
  if (m.time_base == TimeBase::kGps) {
    s.t = GpsTime{m.time_ns};
  } else {
    s.t = GpsTime{gps_from_unix_ns(m.time_ns).ns + host_offset.ns};
  }
  const Vec3 p(m.position[0], m.position[1], m.position[2]);
  s.position = m.position_frame == PositionFrame::kEcef ? geodetic_from_ecef(p)
                                                        : Geodetic{p.x(), p.y(), p.z()};
  const Vec3 v(m.velocity_mps[0], m.velocity_mps[1], m.velocity_mps[2]);
  s.v_ned_mps = m.velocity_frame == VelocityFrame::kEcef ? Vec3(R_ned_from_ecef(s.position) * v) : v;
  if (m.attitude_form == AttitudeForm::kQuaternion)
    s.q_ned_from_body = Quat(m.attitude[0], m.attitude[1], m.attitude[2], m.attitude[3]);
  else
    s.q_ned_from_body = quat_from_euler_rpy(
        Vec3(m.attitude[0], m.attitude[1], m.attitude[2]) * kDegToRad);
  if (m.has_rates) {
    s.f_body_mps2 = Vec3(m.f_body_mps2[0], m.f_body_mps2[1], m.f_body_mps2[2]);
    s.w_ib_body_radps = Vec3(m.w_body_radps[0], m.w_body_radps[1], m.w_body_radps[2]);
  }
  if (m.has_temperature) s.temperature_c = m.temperature_c;
  return s;
}

void ImpairedTruth::set_faults(std::vector<TruthFault> faults, GpsTime start) {
  start_ = start;
  faults_ = std::move(faults);
  for (TruthFault& f : faults_) resolve_start(f.window, start);
  frozen_.assign(faults_.size(), std::nullopt);
}

void ImpairedTruth::add_faults(const std::vector<TruthFault>& faults) {
  faults_.insert(faults_.end(), faults.begin(), faults.end());
  frozen_.resize(faults_.size());
}

std::optional<ImuTruth> ImpairedTruth::at(GpsTime t) {
  const double t_s = seconds_between(t, start_);
  GpsTime query = t;
  for (const TruthFault& f : faults_)
    if (f.kind == TruthFaultKind::kTimeJump && event_level(f.window, t_s) > 0.0) query = query.plus_s(f.jump_s);
  std::optional<ImuTruth> s = inner_->at(query);
  for (std::size_t i = 0; i < faults_.size(); ++i) {
    const TruthFault& f = faults_[i];
    if (event_level(f.window, t_s) <= 0.0) {
      frozen_[i].reset();
      continue;
    }
    if (f.kind == TruthFaultKind::kFreeze) {
      if (!frozen_[i]) frozen_[i] = inner_->at(start_.plus_s(f.window.start_s));
      s = frozen_[i];
    } else if (f.kind == TruthFaultKind::kTeleport && s) {
      s->position = geodetic_from_ecef(ecef_from_geodetic(s->position) +
                                       R_enu_from_ecef(s->position).transpose() * f.offset_enu_m);
    }
  }
  if (s) s->t = t;
  return s;
}

std::unique_ptr<TruthSource> make_truth_source(const TruthSpec& spec, GpsTime start,
                                               GpsTime host_offset) {
  switch (spec.kind) {
    case TruthSourceKind::kStationary:
      return std::make_unique<GeneratorSource>(
          make_trajectory(StationaryTrajectory{spec.position, spec.yaw_deg}, start),
          fmt::format("stationary at {:.6f},{:.6f},{:.1f}", spec.position.lat_deg,
                      spec.position.lon_deg, spec.position.h_m));
    case TruthSourceKind::kCircle:
      return std::make_unique<GeneratorSource>(
          make_trajectory(spec.circle, start),
          fmt::format("circle r {} m at {} m/s, {}", spec.circle.radius_m, spec.circle.speed_mps,
                      count_or_forever(spec.circle.loops, "loops")));
    case TruthSourceKind::kLine:
      return std::make_unique<GeneratorSource>(
          make_trajectory(spec.line, start),
          fmt::format("line {} m at {} m/s, {}", spec.line.length_m, spec.line.speed_mps,
                      count_or_forever(spec.line.passes, "passes")));
    case TruthSourceKind::kWaypoints:
      return std::make_unique<GeneratorSource>(
          make_trajectory(spec.waypoints, start),
          fmt::format("{} waypoints at {} m/s", spec.waypoints.waypoints.size(),
                      spec.waypoints.speed_mps));
    case TruthSourceKind::kCsv:
      return std::make_unique<CsvSource>(spec, start);
    case TruthSourceKind::kUdp:
      return std::make_unique<UdpSource>(spec, host_offset);
  }
  throw std::logic_error("unknown truth source");
}

int truth_udp_port(const TruthSource& source) {
  const auto* udp = dynamic_cast<const UdpSource*>(&source);
  return udp ? udp->port() : 0;
}

}  // namespace navemu
