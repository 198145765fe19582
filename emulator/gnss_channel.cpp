#include "emulator/gnss_channel.hpp"

#include <algorithm>
#include <cmath>

#include "core/sat_table.hpp"
#include "models/geodesy.hpp"

namespace navemu {

namespace {

const char* fix_name(FixType f) {
  switch (f) {
    case FixType::kNone: return "no fix";
    case FixType::kDeadReckoning: return "DR";
    case FixType::k2D: return "2D";
    case FixType::k3D: return "3D";
  }
  return "?";
}

// Smallest k with k * period + offset at or after t.
std::int64_t first_index_at_or_after(GpsTime t, std::int64_t period_ns, std::int64_t offset_ns) {
  const std::int64_t since = t.ns - offset_ns;
  return since / period_ns + (since % period_ns != 0 ? 1 : 0);
}

}  // namespace

void GnssPorts::service() {
  for (auto& p : ports) p->service();
}

GnssChannel::GnssChannel(std::unique_ptr<NavData> nav, const ReceiverParams& receiver,
                         const GnssProfile& profile, ReceiverMode mode, GnssPorts ports,
                         std::vector<std::unique_ptr<EpochRecorder>> recorders)
    : nav_(std::move(nav)),
      receiver_(std::make_unique<Receiver>(*nav_, receiver)),
      device_(make_gnss_device(profile, mode, *nav_)),
      io_(std::move(ports)),
      recorders_(std::move(recorders)),
      period_ns_(device_->period_ns()),
      latency_ns_(std::llround(profile.output_latency_s * 1e9)),
      nominal_rate_hz_(profile.rate_hz) {
  chunk_.reserve(65536);
  replies_.reserve(4096);
  last_fix_.satellites.reserve(kDefinedSatellites);  // copied every epoch: no allocation
  cable_ = receiver.measurement.events.cable;
  resets_ = receiver.measurement.events.resets;
}

std::uint32_t GnssChannel::tracked_systems() const {
  const NavEngineSettings* engine = device_->engine_settings();
  return receiver_->params().measurement.systems & (engine != nullptr ? engine->systems : ~0u);
}

void GnssChannel::begin(GpsTime start) {
  start_ = start;
  receiver_->set_event_origin(start);
  for (CableEvent& c : cable_) resolve_start(c.window, start);
  for (ResetEvent& r : resets_) resolve_start(r.window, start);
  offset_ns_ = device_->grid_offset_ns(start);
  k_ = first_index_at_or_after(start, period_ns_, offset_ns_);
}

std::optional<SensorChannel::Event> GnssChannel::next_event(GpsTime end) const {
  const GpsTime epoch = epoch_time(k_);
  if (!(epoch < end)) return std::nullopt;
  const GpsTime deadline{epoch.ns + latency_ns_};
  return Event{GpsTime{deadline.ns - std::min(kComputeLead_ns, period_ns_ / 2)}, deadline};
}

void GnssChannel::skip_event() {
  ++k_;
  ++skipped_;
}

// Compute ahead, write at the deadline.
bool GnssChannel::run_event(EventContext& ctx) {
  const GpsTime te = epoch_time(k_);
  const std::optional<ImuTruth> tr = ctx.truth.at(te);
  if (const NavEngineSettings* engine = device_->engine_settings()) receiver_->set_engine(*engine);
  // A reset due: the receiver boots (silent), then restarts (models/measurement.hpp ResetEvent).
  const double t_s = seconds_between(te, start_);
  for (auto r = resets_.begin(); r != resets_.end();) {
    if (r->window.start_s > t_s) {
      ++r;
      continue;
    }
    silent_until_ = te.plus_s(kResetSilence_s);
    device_->restart(r->kind, true, silent_until_);
    r = resets_.erase(r);
  }
  silent_ = te < silent_until_ ||
            std::any_of(cable_.begin(), cable_.end(), [&](const CableEvent& c) { return event_level(c.window, t_s) > 0.0; });
  silent_epochs_ += silent_ ? 1 : 0;
  const ReceiverFix& fix = receiver_->update(te, tr ? &*tr : nullptr);
  device_->update(fix, receiver_->measurements(), k_);
  const GpsTime deadline{te.ns + latency_ns_};
  const bool realtime = ctx.clock.realtime();
  if (realtime && ctx.clock.wait_until(deadline) == Clock::Wait::kStopped) return false;
  for (std::size_t i = 0; i < io_.ports.size(); ++i) {
    chunk_.clear();
    device_->encode(io_.receiver_ports[i], chunk_);
    io_.ports[i]->service();
    if (silent_) continue;  // encoded into nowhere
    if (!io_.ports[i]->write(chunk_)) ++chunks_dropped_;
    if (i == 0 && io_.capture_out) io_.capture_out->write(chunk_);
  }
  if (realtime) {
    const double late_ms = static_cast<double>(ctx.clock.monotonic_now() - ctx.clock.mono_of(deadline)) * 1e-6;
    ctx.lateness.add(late_ms);
    if (late_ms > 0.5 * static_cast<double>(period_ns_) * 1e-6) ++late_;
  }
  ++epochs_;
  ++interval_epochs_;
  if (!tr) interval_truth_lost_ = true;
  last_fix_ = device_->reported_fix();
  if (last_fix_.fix != FixType::kNone) ++fixes_;
  last_fix_truth_ = tr;
  const EpochRecord record{te, seconds_between(te, start_), tr, last_fix_};
  for (auto& r : recorders_) r->record(record);
  ++k_;
  follow_rate(te);
  return true;
}

// A client changed the navigation rate or time reference (u-blox CFG-RATE): the next epoch lies
// on the new grid, after the last one sent.
void GnssChannel::follow_rate(GpsTime last) {
  const std::int64_t offset_ns = device_->grid_offset_ns(last);
  if (device_->period_ns() == period_ns_ && offset_ns == offset_ns_) return;
  period_ns_ = device_->period_ns();
  offset_ns_ = offset_ns;
  k_ = std::max(first_index_at_or_after(GpsTime{last.ns + 1}, period_ns_, offset_ns_),
                first_index_at_or_after(start_, period_ns_, offset_ns_));
}

// Commands from the clients, answered on the port they came from.
void GnssChannel::service() {
  for (std::size_t i = 0; i < io_.ports.size(); ++i) {
    transport::BytePort& p = *io_.ports[i];
    for (int n = 0; n < 16; ++n) {  // bounded: a flooding client cannot hold the loop
      const std::size_t len = p.read(input_);
      if (len == 0) break;
      if (silent_) continue;  // the bytes go nowhere
      replies_.clear();
      const std::span<const std::uint8_t> in(input_.data(), len);
      device_->receive(in, io_.receiver_ports[i], replies_);
      if (i == 0 && io_.capture_in) io_.capture_in->write(in);
      if (!replies_.empty()) {
        p.write(replies_);
        if (i == 0 && io_.capture_out) io_.capture_out->write(replies_);
      }
    }
  }
  for (std::size_t i = 0; i < io_.ports.size(); ++i)
    if (const std::optional<int> baud = device_->take_baud_change(io_.receiver_ports[i]))
      transport::set_serial_baud(*io_.ports[i], *baud);
  follow_rate(epoch_time(k_ - 1));
}

void GnssChannel::add_events(const GnssEvents& events) {
  receiver_->add_events(events);
  cable_.insert(cable_.end(), events.cable.begin(), events.cable.end());
  resets_.insert(resets_.end(), events.resets.begin(), events.resets.end());
}

void GnssChannel::clear_events() {
  receiver_->clear_events();
  cable_.clear();
  resets_.clear();
}

void GnssChannel::status(fmt::memory_buffer& out, ChannelStatus& st) {
  const auto o = std::back_inserter(out);
  fmt::format_to(o, "gnss {} ep (", epochs_);
  if (interval_epochs_ == 0) {
    fmt::format_to(o, "no epoch");
  } else {
    fmt::format_to(o, "{} {}/{} sv{}", fix_name(last_fix_.fix), last_fix_.num_used, last_fix_.satellites.size(),
                   silent_ ? ", silent" : "");
    if (last_fix_.fix != FixType::kNone) {
      fmt::format_to(o, " PDOP {:.1f}", last_fix_.dops.pdop);
      if (last_fix_truth_) {
        const Vec3 e = enu_from_ecef(last_fix_.p_ecef_m, last_fix_truth_->position);
        fmt::format_to(o, " err {:.1f} m h {:.1f} m v", std::hypot(e.x(), e.y()), std::abs(e.z()));
      }
    }
  }
  out.push_back(')');
  st.late += static_cast<std::uint64_t>(late_);
  st.skipped += static_cast<std::uint64_t>(skipped_);
  for (const auto& p : io_.ports) st.chunks_dropped += p->counters().chunks_dropped;
  st.truth_lost = st.truth_lost || !last_fix_truth_ || interval_truth_lost_;
  interval_epochs_ = 0;
  interval_truth_lost_ = false;
}

void GnssChannel::flush_logs() {
  for (transport::BytePort* l : {io_.capture_out.get(), io_.capture_in.get()})
    if (l != nullptr) l->service();
}

void GnssChannel::finish(EngineSummary& sum) {
  for (auto& r : recorders_) r->close();
  sum.gnss_epochs = epochs_;
  sum.gnss_fixes = fixes_;
  sum.gnss_skipped = skipped_;
  sum.gnss_late = late_;
  sum.output_chunks_dropped = chunks_dropped_;
  sum.gnss_silent = silent_epochs_;
  for (const auto& p : io_.ports) {
    sum.client_bytes_read += p->counters().bytes_read;
    sum.stale_flushes += p->counters().stale_flushes;
    sum.stale_bytes_flushed += p->counters().stale_bytes_flushed;
  }
  sum.scenario_s = std::max(sum.scenario_s, static_cast<double>(epochs_) / nominal_rate_hz_);
}

}  // namespace navemu
