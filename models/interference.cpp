#include "models/interference.hpp"

#include <algorithm>
#include <cmath>

namespace navemu {
namespace {

double db(double ratio) { return 10.0 * std::log10(ratio); }
double ratio(double db) { return std::pow(10.0, db / 10.0); }

constexpr double kAgcCountsPerDb = 8191.0 / 60.0;
constexpr double kCwIndicatorPerDb = 5.0;

template <typename T>
T clamp_count(double v, double max) {
  return static_cast<T>(std::lround(std::clamp(v, 0.0, max)));
}

}  // namespace

double spectral_separation_q(InterferenceKind k) {
  switch (k) {
    case InterferenceKind::kCw: return 1.0;
    case InterferenceKind::kMatchedSpectrum: return 1.5;
    case InterferenceKind::kWideband: return 2.0;
  }
  return 2.0;
}

void BandInterference::add(double j_over_s_db, InterferenceKind k) {
  const double j = ratio(j_over_s_db);
  j_over_s += j;
  if (k == InterferenceKind::kCw) cw_j_over_s += j;
  j_over_qs += j / spectral_separation_q(k);
}

double effective_cn0_dbhz(double cn0_dbhz, const BandInterference& i, double chip_rate_hz) {
  if (!i.any()) return cn0_dbhz;
  return -db(1.0 / ratio(cn0_dbhz) + i.j_over_qs / chip_rate_hz);
}

std::optional<double> ramped_j_over_s_db(double peak_db, double level) {
  if (level <= 0.0) return std::nullopt;
  return peak_db - (1.0 - std::min(level, 1.0)) * kJammerRampDepth_db;
}

FrontEndMonitor front_end_monitor(const FrontEndReading& open_sky, const BandInterference& i,
                                  double chip_rate_hz) {
  FrontEndMonitor m;
  m.reading = open_sky;
  if (!i.any()) return m;
  const double s_over_n = ratio(kNominalSignalToNoiseDensity_dbhz) / kFrontEndBandwidth_hz;
  const double j_over_n = i.j_over_s * s_over_n;
  const double cw_j_over_n = i.cw_j_over_s * s_over_n;
  if (j_over_n > cw_j_over_n) m.broadband_j_over_n_db = db(j_over_n - cw_j_over_n);
  if (cw_j_over_n > 0.0) m.cw_j_over_n_db = db(cw_j_over_n);

  const double agc_drop_db = db(1.0 + j_over_n);
  m.reading.agc_cnt = clamp_count<std::uint16_t>(open_sky.agc_cnt - kAgcCountsPerDb * agc_drop_db, 8191.0);
  const double noise_rise = 1.0 + ratio(kNominalSignalToNoiseDensity_dbhz) * i.j_over_qs / chip_rate_hz;
  m.reading.noise_per_ms = clamp_count<std::uint16_t>(open_sky.noise_per_ms * noise_rise, 65535.0);
  if (m.cw_j_over_n_db > 0.0)
    m.reading.jam_ind = clamp_count<std::uint8_t>(open_sky.jam_ind + kCwIndicatorPerDb * m.cw_j_over_n_db, 255.0);
  return m;
}

}  // namespace navemu
