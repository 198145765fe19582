#pragma once
// When a scheduled event (`events:`, issue "impairments") acts, and how strongly.

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/time.hpp"

namespace navemu {

// When an event acts: from start_s (or its GPS time `at`) for duration_s, ramping in and out.
struct EventWindow {
  EventWindow() = default;
  EventWindow(double start, double duration, double ramp = 0.0) : start_s(start), duration_s(duration), ramp_s(ramp) {}
  double start_s = 0.0;  // from the scenario's start
  double duration_s = 0.0;
  double ramp_s = 0.0;   // each of ramp-in and ramp-out; at most duration_s / 2
  std::optional<GpsTime> at;  // a start given as GPS time instead: start_s once resolved
};

// Times are exact to the nanosecond, but start_s + duration_s in double is not: an epoch on a
// window's end can come out an ulp inside it (1 in ~1300 starts on a 200 ms grid). An edge is
// where the times say it is, to within half a nanosecond.
inline constexpr double kEventEdgeTolerance_s = 0.5e-9;

// The time since the window's start and until its end, with t within the tolerance of an edge
// taken as on it.
struct EventPhase {
  double in_s, out_s;
};
inline EventPhase event_phase(const EventWindow& w, double t_s) {
  const auto snap = [](double x) { return std::abs(x) < kEventEdgeTolerance_s ? 0.0 : x; };
  return {snap(t_s - w.start_s), snap(w.start_s + w.duration_s - t_s)};
}

// The rate of event_level at t, 1/s: +1/ramp_s on the ramp-in, -1/ramp_s on the ramp-out.
inline double event_level_rate(const EventWindow& w, double t_s) {
  if (w.ramp_s <= 0.0) return 0.0;
  const auto [in, out] = event_phase(w, t_s);
  if (in < 0.0 || out <= 0.0) return 0.0;
  if (in < w.ramp_s && in <= out) return 1.0 / w.ramp_s;
  if (out < w.ramp_s) return -1.0 / w.ramp_s;
  return 0.0;
}

// start_s of a window whose start was given as GPS time, counted from `origin` (the scenario's
// start; negative when the event began before it).
inline void resolve_start(EventWindow& w, GpsTime origin) {
  if (!w.at) return;
  w.start_s = seconds_between(*w.at, origin);
  w.at.reset();
}

// A scheduled event's level at t: 0 before start, rising linearly over ramp_s to 1, 1 until
// ramp_s before the end, falling linearly to 0 at start_s + duration_s (a trapezoid; ramp 0:
// a step).
inline double event_level(const EventWindow& w, double t_s) {
  const auto [in, out] = event_phase(w, t_s);
  if (in < 0.0 || out <= 0.0) return 0.0;
  if (w.ramp_s <= 0.0) return 1.0;
  return std::min({1.0, in / w.ramp_s, out / w.ramp_s});
}

}  // namespace navemu
