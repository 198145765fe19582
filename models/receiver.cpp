#include "models/receiver.hpp"

#include <algorithm>
#include <cmath>

#include "core/sat_table.hpp"
#include "models/reuse.hpp"

namespace navemu {

namespace {
double separation_m(const GeoidGrid* geoid, const Geodetic& p) {
  return geoid ? geoid->separation_m(p.lat_deg, p.lon_deg) : 0.0;
}

double l1_cn0_dbhz(const SatMeasurement& m) { return m.signals[0] ? m.signals[0]->cn0_dbhz : 0.0; }
}  // namespace

Receiver::Receiver(const NavData& nav, const ReceiverParams& p)
    : p_(p), gen_(nav, p.measurement), ideal_rng_(p.measurement.seed, stream_id("ideal_fix")) {
  engine_.elevation_mask_deg = p.measurement.elevation_mask_deg;
  // Room for every satellite: one rising never makes an epoch allocate.
  meas_.sats.reserve(kDefinedSatellites);
  solver_input_.reserve(kDefinedSatellites);
  solution_.sats.reserve(kDefinedSatellites);
  fix_.satellites.reserve(kDefinedSatellites);
}

const ReceiverFix& Receiver::update(GpsTime t, const ImuTruth* truth) {
  ReceiverFix& out = reset_keeping_storage(fix_, &ReceiverFix::satellites);
  out.t = t;
  meas_.sats.clear();
  // The generator's processes need increasing times; a repeated epoch reports no fix.
  if (truth == nullptr || (last_t_ && t <= *last_t_)) return out;
  last_t_ = t;

  const Vec3 p_ecef = ecef_from_geodetic(truth->position);
  const Vec3 v_ecef = R_ned_from_ecef(truth->position).transpose() * truth->v_ned_mps;
  EpochMeasurements& e = meas_;
  gen_.set_active_systems(engine_.systems, engine_.l2_systems);
  gen_.generate(t, p_ecef, v_ecef, e);
  // The receiver keeps its time by its clock solution: a time spoofer's pull moves it.
  out.t = t.plus_s(e.spoofed_time_s);
  out.time_offset_s = seconds_between(e.t_true, t);

  // Channels: the highest satellites when more are in view than the receiver can track.
  if (static_cast<int>(e.sats.size()) > p_.max_channels) {
    std::nth_element(e.sats.begin(), e.sats.begin() + p_.max_channels - 1, e.sats.end(),
                     [](const SatMeasurement& a, const SatMeasurement& b) {
                       return a.dir.el_rad > b.dir.el_rad;
                     });
    e.sats.resize(static_cast<std::size_t>(p_.max_channels));
    std::sort(e.sats.begin(), e.sats.end(),
              [](const SatMeasurement& a, const SatMeasurement& b) { return a.sat < b.sat; });
  }

  // The engine's input filters (F9P integration manual 3.1.7.2 "Navigation input filters"):
  // satellites below the elevation or C/N0 mask are not used, and a fix is attempted only with
  // enough strong satellites. Satellites their broadcast data flag unhealthy are not used
  // either (IS-GPS-200 20.3.3.3.1.4).
  const NavEngineSettings& eng = engine_;
  SolverOptions opt = gen_.solver_options();
  opt.initial_p_ecef_m = last_fix_ecef_m_;
  // Fault detection and exclusion on the residuals, as receivers do (SolverOptions::raim): a
  // satellite whose range is off (a satellite fault, a reflection tracked alone) is left out;
  // a fix that no exclusion makes consistent is kept with its accuracy scaled to its residuals.
  opt.raim = true;
  opt.raim_keeps_failed_fix = true;
  opt.elevation_mask_deg = eng.elevation_mask_deg;
  opt.fix_mode = eng.fix_mode;
  if (eng.fix_mode == SolverFixMode::k2DOnly)  // the fixed height is above mean sea level
    opt.fixed_height_m = eng.fixed_height_msl_m +
                         (last_fix_ecef_m_.isZero() ? 0.0 : separation_m(p_.geoid, geodetic_from_ecef(last_fix_ecef_m_)));
  gen_.solver_input(e, solver_input_);  // one per tracked satellite, in the same order
  int strong = 0;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < e.sats.size(); ++i) {
    const double cn0 = l1_cn0_dbhz(e.sats[i]);
    if (cn0 >= eng.cn0_threshold_dbhz) ++strong;
    if (cn0 >= eng.min_cn0_dbhz && !e.sats[i].unhealthy) solver_input_[kept++] = solver_input_[i];
  }
  solver_input_.resize(kept);
  if (strong < eng.cn0_threshold_sats) solver_input_.clear();
  solve(solver_input_, e.t_receiver, opt, solution_, solver_scratch_);
  Solution& sol = solution_;
  // The dynamic platform model's sanity check (3.1.7.1 "Dynamic platform model details"): a
  // solution beyond its altitude or velocity limits is invalid.
  if (sol.fix != FixType::kNone) {
    const Geodetic g = geodetic_from_ecef(sol.p_ecef_m);
    const Vec3 v_ned = sol.v_ecef_mps ? Vec3(R_ned_from_ecef(g) * *sol.v_ecef_mps) : Vec3(Vec3::Zero());
    if (g.h_m - separation_m(p_.geoid, g) > eng.max_height_msl_m ||
        std::hypot(v_ned.x(), v_ned.y()) > eng.max_h_speed_mps || std::abs(v_ned.z()) > eng.max_v_speed_mps)
      sol.fix = FixType::kNone;
  }

  double sum_sq = 0.0;
  // The solver's satellites are a subsequence of e.sats (solver_input keeps their order).
  std::size_t next_residual = 0;
  for (const SatMeasurement& m : e.sats) {
    ReceiverSatellite s;
    s.sat = m.sat;
    s.az_deg = m.dir.az_rad * kRadToDeg;
    s.el_deg = m.dir.el_rad * kRadToDeg;
    s.cn0_dbhz = l1_cn0_dbhz(m);
    for (std::size_t b = 0; b < m.signals.size(); ++b)
      if (m.signals[b]) s.band_cn0_dbhz[b] = m.signals[b]->cn0_dbhz;
    s.unhealthy = m.unhealthy;
    if (next_residual < sol.sats.size() && sol.sats[next_residual].sat == m.sat) {
      const SatResidual& r = sol.sats[next_residual++];
      if (r.used && sol.fix != FixType::kNone) {
        s.used = true;
        s.smoothed = m.smoothed_noise_fraction < 1.0;
        s.residual_m = r.residual_m;
        sum_sq += r.residual_m * r.residual_m;
      }
    }
    out.satellites.push_back(s);
  }
  if (p_.ideal_sigma_m) {
    const double s = *p_.ideal_sigma_m;
    const Vec3 noise_ned(s * ideal_rng_.normal(), s * ideal_rng_.normal(), s * ideal_rng_.normal());
    out.fix = FixType::k3D;
    out.p_ecef_m = p_ecef + R_ned_from_ecef(truth->position).transpose() * noise_ned;
    out.position = geodetic_from_ecef(out.p_ecef_m);
    out.v_ned_mps = truth->v_ned_mps;
    out.dops = sol.dops;
    out.num_used = static_cast<int>(e.sats.size());
    out.sigma_n_m = out.sigma_e_m = out.sigma_v_m = s;
    out.sigma_h_m = std::sqrt(2.0) * s;
    out.geoid_separation_m = separation_m(p_.geoid, out.position);
    return out;
  }
  if (sol.fix == FixType::kNone) return out;

  out.fix = sol.fix;
  out.p_ecef_m = sol.p_ecef_m;
  out.position = geodetic_from_ecef(sol.p_ecef_m);
  const Mat3 r = R_ned_from_ecef(out.position);
  if (sol.v_ecef_mps) out.v_ned_mps = eng.zero_velocity ? Vec3(Vec3::Zero()) : Vec3(r * *sol.v_ecef_mps);
  out.dops = sol.dops;
  out.num_used = sol.num_used;
  const Mat3 cov_ned = r * sol.cov_ecef_m2 * r.transpose();
  out.sigma_n_m = std::sqrt(std::max(cov_ned(0, 0), 0.0));
  out.sigma_e_m = std::sqrt(std::max(cov_ned(1, 1), 0.0));
  out.sigma_h_m = std::hypot(out.sigma_n_m, out.sigma_e_m);
  out.sigma_v_m = std::sqrt(std::max(cov_ned(2, 2), 0.0));
  out.range_rms_m = sol.num_used > 0 ? std::sqrt(sum_sq / sol.num_used) : 0.0;
  if (out.v_ned_mps && !eng.zero_velocity) {
    const Mat3 cov_v_ned = r * sol.cov_v_ecef_m2ps2 * r.transpose();
    out.sigma_speed_mps = std::sqrt(std::max(cov_v_ned.trace(), 0.0));
    out.sigma_h_speed_mps = std::sqrt(std::max(cov_v_ned(0, 0) + cov_v_ned(1, 1), 0.0));
  }
  out.geoid_separation_m = separation_m(p_.geoid, out.position);
  last_fix_ecef_m_ = sol.p_ecef_m;
  return out;
}

}  // namespace navemu
