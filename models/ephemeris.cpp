// Choice of the broadcast ephemeris record to use at a given time.

#include "models/ephemeris.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <utility>
#include <vector>

namespace navemu {

namespace {

// Time of transmission of a record in ns since the GPS epoch. The RINEX "transmission time of
// message" is seconds of week (RINEX 2.11 section 6.8; it may be given relative to the week of
// toe, hence outside [0, 604800)); it is taken in the week that puts it nearest to toe. Any
// finite value is reduced modulo a week first (a file may hold anything there).
std::int64_t transmission_ns(const GpsEphemeris& e) {
  const std::int64_t week_ns = kSecondsPerWeek * kNsPerS;
  const std::int64_t toe_week_start = e.toe.ns - (((e.toe.ns % week_ns) + week_ns) % week_ns);
  const double tow_s = std::fmod(e.transmission_tow_s, static_cast<double>(kSecondsPerWeek));
  std::int64_t t = toe_week_start + GpsTime::from_seconds(tow_s).ns;
  while (t - e.toe.ns > week_ns / 2) t -= week_ns;
  while (e.toe.ns - t > week_ns / 2) t += week_ns;
  return t;
}

}  // namespace

// Among the healthy records of `sat` (SV health 0, IS-GPS-200 20.3.3.3.1.4), the one whose toe
// is nearest to t: the curve fit interval is centred on toe (IS-GPS-200 20.3.4.5), so the
// nearest toe gives the smallest fit error. When t precedes every toe that is the earliest
// one. Equal distances go to the record transmitted later, then to the later one in the file.
namespace {
const GpsEphemeris* as_pointer(const GpsEphemeris& e) { return &e; }
const GpsEphemeris* as_pointer(const GpsEphemeris* e) { return e; }

// The selection rule over any sequence of records or record pointers.
template <class Records>
const GpsEphemeris* select_among(const Records& records, SatId sat, GpsTime t) {
  const GpsEphemeris* best = nullptr;
  std::int64_t best_dt = 0;
  for (const auto& record : records) {
    const GpsEphemeris* e = as_pointer(record);
    if (e->sat != sat || e->health != 0) continue;
    const std::int64_t dt = t.ns >= e->toe.ns ? t.ns - e->toe.ns : e->toe.ns - t.ns;
    // The transmission times only matter for a tie (they cost as much as the rest).
    if (best == nullptr || dt < best_dt ||
        (dt == best_dt && transmission_ns(*e) >= transmission_ns(*best))) {
      best = e;
      best_dt = dt;
    }
  }
  return best;
}
}  // namespace

const GpsEphemeris* select_ephemeris(const NavData& nav, SatId sat, GpsTime t) {
  return select_among(sat.system() == GnssSystem::kQzss ? nav.qzss : nav.gps, sat, t);
}

namespace {
template <class Record>
const Record* as_record(const Record& e) { return &e; }
template <class Record>
const Record* as_record(const Record* e) { return e; }

// The record of `sat` among `records` (records or pointers to them) with the smallest
// |t - reference time| within max_age_s that `usable` accepts; ties go to the later one.
template <class Records, class Usable>
auto nearest_record(const Records& records, SatId sat, GpsTime t, double max_age_s,
                    Usable usable) {
  decltype(as_record(*std::begin(records))) best = nullptr;
  double best_age_s = max_age_s;
  for (const auto& record : records) {
    const auto* e = as_record(record);
    if (e->sat != sat || !usable(*e)) continue;
    const double age_s = std::abs(seconds_between(t, reference_time(*e)));
    if (age_s <= best_age_s) {
      best = e;
      best_age_s = age_s;
    }
  }
  return best;
}

template <class Records>
const GalileoEphemeris* galileo_rule(const Records& records, SatId sat, GpsTime t) {
  constexpr int kE1bHealth = 0x7;
  const auto usable = [t](bool inav) {
    return [t, inav](const GalileoEphemeris& e) {
      return e.inav_clock() == inav && (e.health & kE1bHealth) == 0 && e.toe <= t;
    };
  };
  const GalileoEphemeris* inav = nearest_record(records, sat, t, kMaxEphemerisAge_s, usable(true));
  return inav ? inav : nearest_record(records, sat, t, kMaxEphemerisAge_s, usable(false));
}
template <class Records>
const BeidouEphemeris* beidou_rule(const Records& records, SatId sat, GpsTime t) {
  return nearest_record(records, sat, t, kMaxEphemerisAge_s,
                        [](const BeidouEphemeris& e) { return e.health == 0; });
}
template <class Records>
const GlonassEphemeris* glonass_rule(const Records& records, SatId sat, GpsTime t) {
  return nearest_record(records, sat, t, kMaxGlonassAge_s,
                        [](const GlonassEphemeris& e) { return e.health == 0; });
}
}  // namespace

const GalileoEphemeris* select_galileo_ephemeris(const NavData& nav, SatId sat, GpsTime t) {
  return galileo_rule(nav.galileo, sat, t);
}
const BeidouEphemeris* select_beidou_ephemeris(const NavData& nav, SatId sat, GpsTime t) {
  return beidou_rule(nav.beidou, sat, t);
}
const GlonassEphemeris* select_glonass_ephemeris(const NavData& nav, SatId sat, GpsTime t) {
  return glonass_rule(nav.glonass, sat, t);
}

const GalileoEphemeris* select_galileo_ephemeris(std::span<const GalileoEphemeris* const> records,
                                                 GpsTime t) {
  return records.empty() ? nullptr : galileo_rule(records, records.front()->sat, t);
}
const BeidouEphemeris* select_beidou_ephemeris(std::span<const BeidouEphemeris* const> records,
                                               GpsTime t) {
  return records.empty() ? nullptr : beidou_rule(records, records.front()->sat, t);
}
const GlonassEphemeris* select_glonass_ephemeris(std::span<const GlonassEphemeris* const> records,
                                                 GpsTime t) {
  return records.empty() ? nullptr : glonass_rule(records, records.front()->sat, t);
}

BroadcastRecord select_record(const NavData& nav, SatId sat, GpsTime t) {
  switch (sat.system()) {
    case GnssSystem::kGps:
    case GnssSystem::kQzss:
      if (const GpsEphemeris* e = select_ephemeris(nav, sat, t);
          e && std::abs(seconds_between(t, e->toe)) <= kMaxEphemerisAge_s)
        return e;
      return {};
    case GnssSystem::kGalileo:
      if (const GalileoEphemeris* e = select_galileo_ephemeris(nav, sat, t)) return e;
      return {};
    case GnssSystem::kBeidou:
      if (const BeidouEphemeris* e = select_beidou_ephemeris(nav, sat, t)) return e;
      return {};
    case GnssSystem::kGlonass:
      if (const GlonassEphemeris* e = select_glonass_ephemeris(nav, sat, t)) return e;
      return {};
    default: return {};
  }
}

GpsTime reference_time(const BroadcastRecord& r) {
  return std::visit(
      [](const auto& p) -> GpsTime {
        if constexpr (std::is_same_v<std::decay_t<decltype(p)>, std::monostate>)
          return GpsTime{};
        else
          return reference_time(*p);
      },
      r);
}

const GpsEphemeris* select_ephemeris(std::span<const GpsEphemeris* const> records, GpsTime t) {
  return records.empty() ? nullptr : select_among(records, records.front()->sat, t);
}

EphemerisSelection select_ephemeris_span(std::span<const GpsEphemeris* const> records,
                                         GpsTime t) {
  EphemerisSelection out;
  out.eph = select_ephemeris(records, t);
  out.after_2ns = std::numeric_limits<std::int64_t>::min();
  out.before_2ns = std::numeric_limits<std::int64_t>::max();
  if (out.eph == nullptr) return out;  // no healthy record: none at any time
  for (const GpsEphemeris* e : records) {
    if (e->sat != out.eph->sat || e->health != 0 || e->toe == out.eph->toe) continue;
    const std::int64_t midpoint_2ns = e->toe.ns + out.eph->toe.ns;
    if (e->toe > out.eph->toe)
      out.before_2ns = std::min(out.before_2ns, midpoint_2ns);
    else
      out.after_2ns = std::max(out.after_2ns, midpoint_2ns);
  }
  return out;
}

TimeSpan fit_interval(const GpsEphemeris& e) {
  const double half_s = std::max(e.fit_interval_h, 4.0) * 3600.0 / 2.0;
  return {e.toe.plus_s(-half_s), e.toe.plus_s(half_s)};
}

std::vector<TimeSpan> covered_spans(const NavData& nav, int min_satellites) {
  if (nav.renews)
    return {{GpsTime{std::numeric_limits<std::int64_t>::min()},
             GpsTime{std::numeric_limits<std::int64_t>::max()}}};
  min_satellites = std::max(min_satellites, 1);
  std::map<SatId, std::vector<TimeSpan>> by_sat;
  for (const GpsEphemeris& e : nav.gps)
    if (e.health == 0) by_sat[e.sat].push_back(fit_interval(e));
  // Each satellite's fit intervals merged (a satellite counts once however many of its records
  // hold), then a sweep over where they begin (+1) and end (-1). At equal times beginnings come
  // first, so satellites whose spans touch count together at that instant.
  std::vector<std::pair<GpsTime, int>> events;
  for (auto& [sat, spans] : by_sat) {
    std::sort(spans.begin(), spans.end(), [](const TimeSpan& a, const TimeSpan& b) { return a.from < b.from; });
    TimeSpan cur = spans.front();
    for (const TimeSpan& s : spans) {
      if (s.from > cur.to) {
        events.insert(events.end(), {{cur.from, +1}, {cur.to, -1}});
        cur = s;
      } else {
        cur.to = std::max(cur.to, s.to);
      }
    }
    events.insert(events.end(), {{cur.from, +1}, {cur.to, -1}});
  }
  std::sort(events.begin(), events.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first < b.first : a.second > b.second;
  });
  std::vector<TimeSpan> out;
  int count = 0;
  for (const auto& [t, step] : events) {
    const bool was = count >= min_satellites;
    count += step;
    if (!was && count >= min_satellites) out.push_back({t, t});
    if (was && count < min_satellites) out.back().to = t;
  }
  return out;
}

}  // namespace navemu
