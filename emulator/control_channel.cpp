#include "emulator/control_channel.hpp"

#include <algorithm>

#include <fmt/format.h>

namespace navemu {

void ControlChannel::service() {
  if (port_) port_->service([this](std::string_view line) { return apply(line); });
}

std::string ControlChannel::apply(std::string_view line) {
  const auto refuse = [this](std::string_view why) {
    ++refused_;
    return fmt::format(R"({{"ok": false, "error": {}}})", json_string(why));
  };
  const std::variant<ControlCommand, std::string> parsed = parse_control_line(line);
  if (const std::string* why = std::get_if<std::string>(&parsed)) return refuse(*why);
  const ControlCommand& cmd = std::get<ControlCommand>(parsed);
  if (std::holds_alternative<ControlClear>(cmd)) {
    if (to_.gnss) to_.gnss->clear_events();
    if (to_.imu) to_.imu->clear_faults();
    if (to_.truth) to_.truth->set_faults({}, start_);
    ++accepted_;
    return R"({"ok": true})";
  }
  ControlEvent e = std::get<ControlEvent>(cmd);
  // The one event's window, on the scenario's clock: from its GPS time, or from "now": the next
  // instant the channels it acts on have not yet measured. A receiver's event starts at its
  // next epoch and an IMU fault at its next sample; a truth fault at the later of the two, as
  // each channel runs ahead of the other by up to its own output latency (the receiver's
  // epoch goes out some 40 ms after the IMU has measured past it).
  EventWindow* w = nullptr;
  e.events.for_each_window([&](EventWindow& x) { w = &x; });
  for (ImuFault& f : e.imu) w = &f.window;
  for (TruthFault& f : e.truth) w = &f.window;
  if (w == nullptr) return refuse("no event");
  if (e.events.size() > 0 && !to_.gnss) return refuse("this run has no GNSS receiver (gnss.enabled)");
  if (!e.imu.empty() && !to_.imu) return refuse("this run has no IMU (imu.enabled)");
  if (!e.truth.empty() && !to_.truth) return refuse("this run's truth takes no faults");
  if (w->at) {
    resolve_start(*w, start_);
  } else {
    GpsTime now = start_;
    if (to_.gnss && (e.events.size() > 0 || !e.truth.empty())) now = std::max(now, to_.gnss->next_epoch());
    if (to_.imu && (!e.imu.empty() || !e.truth.empty())) now = std::max(now, to_.imu->next_sample());
    w->start_s += seconds_between(now, start_);
  }
  if (!e.imu.empty())
    if (const std::optional<std::string> why = to_.imu->add_faults(e.imu)) return refuse(*why);
  if (e.events.size() > 0) to_.gnss->add_events(e.events);
  if (!e.truth.empty()) to_.truth->add_faults(e.truth);
  ++accepted_;
  const GpsTime from = start_.plus_s(w->start_s);
  return fmt::format(R"({{"ok": true, "from": "{}", "gps": "{}"}})", format_iso_utc(from), format_week_tow(from));
}

void ControlChannel::status(fmt::memory_buffer& out, ChannelStatus&) {
  fmt::format_to(std::back_inserter(out), "ctl {} ok {} refused", accepted_, refused_);
}

}  // namespace navemu
