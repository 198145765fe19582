#include "emulator/imu_can.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <algorithm>
#include <array>
#include <ostream>
#include <stdexcept>

namespace navemu {

namespace {

bool needs_fd(const std::vector<CanLayout>& layouts) {
  return std::find(layouts.begin(), layouts.end(), CanLayout::kHighResFd) != layouts.end();
}

std::unique_ptr<transport::FramePort> open_one(const CanOutputSpec& o) {
  if (o.type == "socketcan") return transport::open_socketcan({o.interface, needs_fd(o.layouts)});
  if (o.type == "slcan") {
    std::unique_ptr<transport::BytePort> bytes =
        o.device.empty() ? transport::open_pty({o.link, 4096})
                         : transport::open_serial({o.device, o.baud, 4096});
    return transport::open_slcan(std::move(bytes), {o.auto_open});
  }
  return transport::open_candump_log({o.path, o.interface});
}

transport::CanFrameView view(const can::CanFrame& f) {
  return {f.id, f.extended, f.fd, false, std::span<const std::uint8_t>(f.data.data(), f.len)};
}

}  // namespace

ImuCanOutputs::ImuCanOutputs(const std::vector<CanOutputSpec>& specs, const CanSettings& settings,
                             std::ostream& log)
    : j1939_{settings.priority, settings.source_address},
      highres_{settings.base_id, settings.extended} {
  for (const CanOutputSpec& spec : specs) {
    Output out{nullptr, spec.layouts};
    try {
      out.port = open_one(spec);
    } catch (const std::runtime_error& e) {
      if (spec.fallback.empty()) throw;
      out.port = open_one(spec.fallback.front());
      fmt::print(log, "navemu: IMU: {}; CAN frames go to {} instead\n", e.what(),
                 out.port->describe());
    }
    if (needs_fd(spec.layouts) && !out.port->fd_capable())
      throw std::runtime_error(fmt::format("{}: layout highres-fd needs CAN FD", out.port->describe()));
    for (CanLayout l : spec.layouts) {
      uses_j1939_ |= l == CanLayout::kJ1939;
      uses_highres_ |= l == CanLayout::kHighRes;
      uses_fd_ |= l == CanLayout::kHighResFd;
    }
    outputs_.push_back(std::move(out));
  }
}

void ImuCanOutputs::send(const can::ImuSample& sample, std::int64_t unix_time_ns) {
  // Each layout in use is encoded once per sample, whatever the number of outputs using it.
  if (uses_j1939_)
    j1939_frames_ = {can::j1939::encode_ari(sample, j1939_), can::j1939::encode_accs(sample, j1939_)};
  if (uses_highres_) highres_frames_ = can::highres::encode_classic(sample, highres_);
  if (uses_fd_) fd_frame_ = can::highres::encode_fd(sample, highres_);
  for (Output& out : outputs_) {
    for (CanLayout layout : out.layouts) {
      const std::span<const can::CanFrame> frames =
          layout == CanLayout::kJ1939     ? std::span<const can::CanFrame>(j1939_frames_)
          : layout == CanLayout::kHighRes ? std::span<const can::CanFrame>(highres_frames_)
                                          : std::span<const can::CanFrame>(&fd_frame_, 1);
      std::array<transport::CanFrameView, can::highres::kClassicFrameCount> views;  // the most
      const std::size_t n = std::min(frames.size(), views.size());
      for (std::size_t i = 0; i < n; ++i) views[i] = view(frames[i]);
      out.port->write_burst(std::span<const transport::CanFrameView>(views.data(), n), unix_time_ns);
    }
  }
}

void ImuCanOutputs::send_error(std::uint32_t error_class, const std::array<std::uint8_t, 8>& data,
                               std::int64_t unix_time_ns) {
  transport::CanFrameView f;
  f.id = error_class;
  f.error = true;
  f.data = data;
  for (Output& out : outputs_)
    if (out.port->carries_error_frames()) out.port->write(f, unix_time_ns);
}

void ImuCanOutputs::service() {
  for (Output& out : outputs_) out.port->service();
}

std::vector<std::string> ImuCanOutputs::describe() const {
  std::vector<std::string> lines;
  for (const Output& out : outputs_) {
    std::string names;
    for (CanLayout l : out.layouts) names += (names.empty() ? "" : ", ") + std::string(can_layout_name(l));
    lines.push_back(fmt::format("{}: {}", out.port->describe(), names));
  }
  return lines;
}

CanOutputTotals ImuCanOutputs::totals() const {
  CanOutputTotals t;
  for (const Output& out : outputs_) {
    const transport::CanCounters& c = out.port->counters();
    t.frames_written += c.frames_written;
    t.frames_dropped += c.frames_dropped;
    t.frames_held += c.frames_held;
    t.frames_failed += c.frames_failed;
    t.bus_errors += c.bus_errors;
    t.errors += c.errors;
  }
  return t;
}

std::vector<CanOutputSpec> offline_can_outputs(const std::vector<CanOutputSpec>& configured,
                                               const std::string& path) {
  CanOutputSpec log;
  log.type = "candump";
  log.path = path;
  log.interface = "can0";
  log.layouts.clear();
  bool named = false;
  for (const CanOutputSpec& o : configured) {
    if (o.type == "socketcan" && !named) {
      log.interface = o.interface;
      named = true;
    }
    for (CanLayout l : o.layouts)
      if (std::find(log.layouts.begin(), log.layouts.end(), l) == log.layouts.end())
        log.layouts.push_back(l);
  }
  if (log.layouts.empty()) log.layouts.push_back(CanLayout::kJ1939);
  return {log};
}

}  // namespace navemu
