#include "models/solver.hpp"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>

#include "models/orbit.hpp"
#include "models/reuse.hpp"

namespace navemu {

namespace {

using Mat4 = Eigen::Matrix4d;
// Row-bounded matrices: Eigen keeps them on the stack (no allocation per epoch).
constexpr int kMaxRows = static_cast<int>(kMaxSolverSatellites) + 1;  // + the height constraint
using MatN4 = Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::ColMajor, kMaxRows, 4>;
using VecN = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxRows, 1>;
// The position and a clock per clock group in the solution (kClockGroups).
constexpr int kMaxUnknowns = 3 + static_cast<int>(kClockGroups);
using MatX = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, kMaxUnknowns,
                           kMaxUnknowns>;
using VecX = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxUnknowns, 1>;

// An ECEF position is taken as known once it is away from the Earth's centre.
bool position_known(const Vec3& p) { return p.norm() > 1e3; }

// Variance of the tropospheric model error, sigma_m / (sin(el) + 0.1) (RTKLIB's ERR_SAAS with
// sigma_m = 0.3 m), growing toward the horizon.
double tropo_variance_m2(double sigma_m, double sin_el) {
  const double s = sigma_m / (sin_el + 0.1);
  return s * s;
}

struct Row {
  Vec3 u = Vec3::Zero();  // unit line of sight, receiver to satellite (ECEF)
  double residual_m = 0.0;
  double variance_m2 = 1.0;
  std::size_t index = 0;
  std::size_t group = 0;  // clock_group of the satellite's system
};

// Code noise scale of a system relative to GPS's (SolverOptions::sigma_a_m).
double code_sigma_factor(GnssSystem s) {
  switch (s) {
    case GnssSystem::kGlonass: return 1.5;
    case GnssSystem::kSbas: return 3.0;
    default: return 1.0;
  }
}

// Upper bound of the URA bin a broadcast accuracy falls in (IS-GPS-200 20.3.3.3.1.3: URA
// index N covers (bound[N-1], bound[N]] metres); 6144 m and beyond: index 15, no accuracy.
double ura_upper_bound_m(double ura_m) {
  static constexpr double kBound_m[] = {2.4,  3.4,   4.85,  6.85,  9.65,   13.65,  24.0,  48.0,
                                        96.0, 192.0, 384.0, 768.0, 1536.0, 3072.0, 6144.0};
  for (double b : kBound_m)
    if (ura_m <= b) return b;
  return 6144.0;
}

}  // namespace

Dops dops_from_directions(std::span<const AzEl> all) {
  std::array<Direction, kMaxRows> dirs;
  const std::size_t n = std::min<std::size_t>(all.size(), kMaxRows);
  for (std::size_t i = 0; i < n; ++i) dirs[i] = direction(all[i]);
  return dops_from_directions(std::span<const Direction>(dirs.data(), n));
}

Dops dops_from_directions(std::span<const Direction> all) {
  Dops d;
  const std::span<const Direction> dirs = all.first(std::min<std::size_t>(all.size(), kMaxRows));
  if (dirs.size() < 4) return d;
  MatN4 h(static_cast<Eigen::Index>(dirs.size()), 4);
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    const auto r = static_cast<Eigen::Index>(i);
    h(r, 0) = -dirs[i].cos_el * dirs[i].sin_az;
    h(r, 1) = -dirs[i].cos_el * dirs[i].cos_az;
    h(r, 2) = -dirs[i].sin_el;
    h(r, 3) = 1.0;
  }
  const Mat4 n = h.transpose() * h;
  Eigen::FullPivLU<Mat4> lu(n);
  if (!lu.isInvertible()) return d;
  const Mat4 q = lu.inverse();
  d.gdop = std::sqrt(q.trace());
  d.pdop = std::sqrt(q(0, 0) + q(1, 1) + q(2, 2));
  d.hdop = std::sqrt(q(0, 0) + q(1, 1));
  d.vdop = std::sqrt(q(2, 2));
  d.tdop = std::sqrt(q(3, 3));
  return d;
}

namespace {
// The measurement from any Kepler record: `group_delay_s` is the signal's TGD/BGD.
RangeMeasurement kepler_measurement(const KeplerEphemeris& eph, GpsTime t_receive,
                                    double pseudorange_m, double group_delay_s,
                                    double variance_m2, double carrier_hz,
                                    std::optional<double> doppler_hz, const SatStateAt* near) {
  GpsTime t_tx = t_receive.plus_s(-pseudorange_m / kSpeedOfLight_mps);
  t_tx = t_tx.plus_s(-gps_sat_clock_poly_s(eph, t_tx));
  constexpr double kCarryAtMost_s = 1e-3;
  SatState s;
  if (const double dt_s = near != nullptr ? seconds_between(t_tx, near->t) : kCarryAtMost_s;
      std::abs(dt_s) < kCarryAtMost_s) {
    s = near->state;
    s.p_ecef_m += s.v_ecef_mps * dt_s;
    s.clock_bias_s += s.clock_drift_sps * dt_s;
  } else {
    s = broadcast_sat_state(eph, t_tx);
  }
  RangeMeasurement m;
  m.sat = eph.sat;
  m.sat_p_ecef_m = s.p_ecef_m;
  m.sat_v_ecef_mps = s.v_ecef_mps;
  m.sat_clock_m = kSpeedOfLight_mps * (s.clock_bias_s - group_delay_s);
  m.sat_clock_drift_mps = kSpeedOfLight_mps * s.clock_drift_sps;
  m.pseudorange_m = pseudorange_m;
  m.sat_variance_m2 = variance_m2;
  m.carrier_hz = carrier_hz;
  if (doppler_hz) m.range_rate_mps = -*doppler_hz * kSpeedOfLight_mps / carrier_hz;
  return m;
}
}  // namespace

RangeMeasurement make_range_measurement(const GpsEphemeris& eph, GpsTime t_receive, double pseudorange_m,
                                        std::optional<double> doppler_l1_hz, const SatStateAt* near) {
  const double ura = ura_upper_bound_m(eph.ura_m);
  return kepler_measurement(eph, t_receive, pseudorange_m, eph.tgd_s, ura * ura, kGpsL1_Hz,
                            doppler_l1_hz, near);
}

RangeMeasurement make_range_measurement(const GalileoEphemeris& eph, GpsTime t_receive, double pseudorange_m,
                                        std::optional<double> doppler_e1_hz, const SatStateAt* near) {
  const double sisa_m = eph.sisa_m > 0.0 ? eph.sisa_m : 500.0;
  return kepler_measurement(eph, t_receive, pseudorange_m, eph.bgd_e1_s(), sisa_m * sisa_m,
                            carrier_frequency_hz(kGalileoE1C), doppler_e1_hz, near);
}

RangeMeasurement make_range_measurement(const BeidouEphemeris& eph, GpsTime t_receive, double pseudorange_m,
                                        std::optional<double> doppler_b1i_hz, const SatStateAt* near) {
  const double ura = ura_upper_bound_m(eph.ura_m);
  return kepler_measurement(eph, t_receive, pseudorange_m, eph.tgd1_s, ura * ura,
                            carrier_frequency_hz(kBeidouB1I), doppler_b1i_hz, near);
}

RangeMeasurement make_range_measurement(const GlonassEphemeris& eph, GpsTime t_receive,
                                        double pseudorange_m, std::optional<double> doppler_l1_hz,
                                        const GlonassArc* arc) {
  constexpr double kGlonassEphemerisSigma_m = 5.0;  // RTKLIB's ERREPH_GLO
  GpsTime t_tx = t_receive.plus_s(-pseudorange_m / kSpeedOfLight_mps);
  t_tx = t_tx.plus_s(-glonass_sat_clock_s(eph, t_tx));
  const SatState s = arc != nullptr && arc->of(eph) ? arc->state(t_tx) : glonass_sat_state(eph, t_tx);
  RangeMeasurement m;
  m.sat = eph.sat;
  m.sat_p_ecef_m = s.p_ecef_m;
  m.sat_v_ecef_mps = s.v_ecef_mps;
  m.sat_clock_m = kSpeedOfLight_mps * s.clock_bias_s;
  m.sat_clock_drift_mps = kSpeedOfLight_mps * s.clock_drift_sps;
  m.pseudorange_m = pseudorange_m;
  m.sat_variance_m2 = kGlonassEphemerisSigma_m * kGlonassEphemerisSigma_m;
  m.carrier_hz = carrier_frequency_hz(kGlonassL1OF, eph.frequency_channel);
  if (doppler_l1_hz) m.range_rate_mps = -*doppler_l1_hz * kSpeedOfLight_mps / m.carrier_hz;
  return m;
}

RangeMeasurement make_range_measurement(const BroadcastRecord& r, GpsTime t_receive,
                                        double pseudorange_m, std::optional<double> doppler_hz,
                                        const GlonassArc* glonass_arc, const SatStateAt* near) {
  return std::visit(
      [&](const auto& record) -> RangeMeasurement {
        using Record = std::decay_t<decltype(record)>;
        if constexpr (std::is_same_v<Record, std::monostate>)
          return {};
        else if constexpr (std::is_same_v<Record, const GlonassEphemeris*>)
          return make_range_measurement(*record, t_receive, pseudorange_m, doppler_hz, glonass_arc);
        else
          return make_range_measurement(*record, t_receive, pseudorange_m, doppler_hz, near);
      },
      r);
}

Solution solve(const std::vector<RangeMeasurement>& meas, GpsTime t, const SolverOptions& opt) {
  Solution sol;
  solve(meas, t, opt, sol);
  return sol;
}

namespace {
// One weighted least-squares solution (no residual test).
void solve_least_squares(std::span<const RangeMeasurement> all, GpsTime t, const SolverOptions& opt,
                         Solution& sol) {
  const std::span<const RangeMeasurement> meas =
      all.first(std::min(all.size(), kMaxSolverSatellites));
  reset_keeping_storage(sol, &Solution::sats).sats.resize(meas.size());
  Vec3 p = opt.initial_p_ecef_m;
  std::array<double, kClockGroups> clk{};  // per clock group
  const bool prior_known = position_known(p);
  // Geodetic coordinates of the estimate, kept for the position they were computed at (the
  // prior's serve the held height and the first iteration's corrections).
  Vec3 geo_at = Vec3::Zero();
  Geodetic geo_of_p;
  bool geo_valid = false;
  auto geodetic_of = [&](const Vec3& q) {
    if (!geo_valid || q != geo_at) {
      geo_of_p = geodetic_from_ecef(q);
      geo_at = q;
      geo_valid = true;
    }
    return geo_of_p;
  };
  const double h_hold_m = opt.fix_mode == SolverFixMode::k2DOnly ? opt.fixed_height_m
                         : prior_known                           ? geodetic_of(p).h_m
                                                                 : 0.0;
  const double tow_s = to_week_tow(t).tow_s;  // for the Klobuchar model
  const double mask_rad = opt.elevation_mask_deg * kDegToRad;
  const double sa2 = opt.sigma_a_m * opt.sigma_a_m;
  const double sb2 = opt.sigma_b_m * opt.sigma_b_m;

  std::array<Row, kMaxSolverSatellites> row_store;
  // Each satellite's direction (the weights use its sin(elevation), the DOPs all of it).
  std::array<Direction, kMaxSolverSatellites> dirs;
  std::size_t n_sat_rows = 0;
  bool converged = false;
  Eigen::FullPivLU<MatX> lu;  // of the last iteration's normal equations
  // Column of each clock group's clock in the last iteration (0: not in the solution).
  std::array<Eigen::Index, kClockGroups> clock_column{};
  bool hold_height = false;
  // The elevation mask applies once the estimate is within 10 km (elevations then good to
  // ~0.1 deg): from the first iteration with a prior, otherwise after the first large steps
  // from the Earth's centre, whose intermediate estimates can be hundreds of km off.
  bool settled = prior_known;

  // Iterated weighted least squares on the linearised pseudorange equations
  // P = |R(w tau) p_sat - p| + c dt_rx - c dt_sat + I + T  (RTKLIB pntpos / ESA GNSS Book I, 6.1).
  // Directions and the ionosphere change by well under a millimetre while the estimate moves
  // less than kReuseDirections_m (elevations by ~5e-7 rad, the pierce points as much); the
  // troposphere by ~0.3 mm per metre of height at the zenith (~3 mm at 5 deg), so it is
  // recomputed once the estimate has moved kReuseTropo_m.
  constexpr double kReuseDirections_m = 10.0, kReuseTropo_m = 1.0;
  Vec3 directions_at = Vec3::Zero(), tropo_at = Vec3::Zero();  // where computed; zero: not yet
  for (int iter = 0; iter < opt.max_iterations; ++iter) {
    n_sat_rows = 0;
    const bool known = position_known(p);
    const bool new_directions = !known || !position_known(directions_at) ||
                                (p - directions_at).norm() > kReuseDirections_m;
    const bool new_tropo = new_directions || (p - tropo_at).norm() > kReuseTropo_m;
    Geodetic geo;
    Mat3 r_enu = Mat3::Identity();
    SaastamoinenZenith tropo_zenith;
    if (known && new_tropo) {
      geo = geodetic_of(p);
      if (new_directions) r_enu = R_enu_from_ecef(geo);
      if (opt.saastamoinen) {
        // RTKLIB's Saastamoinen has no delay below -100 m (atmosphere.cpp); an estimate near that
        // height (the sea south of Sri Lanka, geoid -106 m, or a fix pulled down by errors) then
        // flips between two solutions 10 m apart and never converges. Below it the model is
        // taken at -100 m (continuous; rnx2rtkp differs only there).
        Geodetic at = geo;
        at.h_m = std::max(at.h_m, kSaastamoinenLowest_m);
        tropo_zenith = saastamoinen_zenith(at, standard_atmosphere(at.h_m, opt.relative_humidity));
      }
    }
    if (new_directions) directions_at = known ? p : Vec3::Zero();
    if (new_tropo) tropo_at = known ? p : Vec3::Zero();
    for (std::size_t i = 0; i < meas.size(); ++i) {
      const RangeMeasurement& m = meas[i];
      SatResidual& out = sol.sats[i];
      // Earth rotation during the signal's flight (Sagnac).
      const double tau_s = (m.sat_p_ecef_m - p).norm() / kSpeedOfLight_mps;
      const Vec3 p_sat = rotate_earth(m.sat_p_ecef_m, tau_s);
      const Vec3 los = p_sat - p;
      const double range = los.norm();
      if (new_directions) {
        out = SatResidual{};
        out.sat = m.sat;
        dirs[i] = known ? direction(r_enu, p, p_sat) : Direction{{0.0, kPi / 2.0}, 1.0, 0.0, 0.0, 1.0};
        const Direction& dir = dirs[i];
        out.az_deg = dir.az_el.az_rad * kRadToDeg;
        out.el_deg = dir.az_el.el_rad * kRadToDeg;
        // The L1 delay scaled to the signal's frequency, 1/f^2 (IS-GPS-200 20.3.3.3.3.3).
        if (known && opt.klobuchar) {
          const double l1_over_f = kGpsL1_Hz / m.carrier_hz;
          out.iono_m = kSpeedOfLight_mps * klobuchar_delay_l1_s(*opt.klobuchar, geo, dir, tow_s) *
                       l1_over_f * l1_over_f;
        }
      }
      if (new_tropo && known && opt.saastamoinen)
        out.tropo_m = saastamoinen_delay(tropo_zenith, out.el_deg * kDegToRad).total_m();
      out.residual_m = 0.0;
      out.used = false;
      const double el_rad = out.el_deg * kDegToRad;
      if (settled && el_rad < mask_rad) continue;
      const std::size_t group = clock_group(m.sat.system());
      out.residual_m =
          m.pseudorange_m - (range + clk[group] - m.sat_clock_m + out.iono_m + out.tropo_m);
      out.used = true;
      const double f = code_sigma_factor(m.sat.system());
      double var = m.code_variance_m2.value_or(f * f * (sa2 + sb2 / dirs[i].sin_el)) + m.sat_variance_m2;
      if (known && opt.klobuchar) {
        const double iono_sigma_m = opt.iono_error_fraction * out.iono_m;
        var += iono_sigma_m * iono_sigma_m;
      }
      if (known && opt.saastamoinen) var += tropo_variance_m2(opt.tropo_sigma_m, dirs[i].sin_el);
      row_store[n_sat_rows++] = Row{los / range, out.residual_m, var, i, group};
    }
    // Unknowns: the position, then the clock of each group with a satellite in use.
    clock_column.fill(0);
    for (std::size_t k = 0; k < n_sat_rows; ++k) clock_column[row_store[k].group] = 1;
    Eigen::Index nx = 3;
    for (Eigen::Index& c : clock_column)
      if (c != 0) c = nx++;

    switch (opt.fix_mode) {
      case SolverFixMode::kAuto:
        hold_height = n_sat_rows == static_cast<std::size_t>(nx - 1) && prior_known;
        break;
      case SolverFixMode::k3DOnly: hold_height = false; break;
      case SolverFixMode::k2DOnly: hold_height = settled; break;
    }
    const std::size_t n_rows = n_sat_rows + (hold_height ? 1 : 0);
    if (n_sat_rows < static_cast<std::size_t>(nx - 1) || n_rows < static_cast<std::size_t>(nx))
      break;

    // Normal equations N = H^T W H and H^T W v, accumulated row by row: row (-u^T, 1 in the
    // column of the satellite's clock) with weight 1 / variance.
    MatX n = MatX::Zero(nx, nx);
    VecX hwv = VecX::Zero(nx);
    for (std::size_t k = 0; k < n_sat_rows; ++k) {
      const Row& r = row_store[k];
      const double w = 1.0 / r.variance_m2;
      const Eigen::Index c = clock_column[r.group];
      const Vec3 wu = w * r.u;
      n.topLeftCorner<3, 3>().noalias() += wu * r.u.transpose();
      n.block<3, 1>(0, c) -= wu;
      n(c, c) += w;
      hwv.head<3>() -= wu * r.residual_m;
      hwv(c) += w * r.residual_m;
    }
    n.bottomLeftCorner(nx - 3, 3) = n.topRightCorner(3, nx - 3).transpose();
    if (hold_height) {
      // Pseudo-observation: the height stays at the prior height (1 cm sigma).
      const Geodetic g = geodetic_of(p);
      const Vec3 up = R_enu_from_ecef(g).row(2).transpose();
      n.topLeftCorner<3, 3>().noalias() += 1e4 * up * up.transpose();
      hwv.head<3>() += 1e4 * up * (h_hold_m - g.h_m);
    }
    lu.compute(n);
    if (!lu.isInvertible()) break;
    const VecX dx = lu.solve(hwv);
    p += dx.head<3>();
    for (std::size_t g = 0; g < kClockGroups; ++g)
      if (clock_column[g] != 0) clk[g] += dx(clock_column[g]);
    settled = settled || dx.head<3>().norm() < 1e4;
    sol.iterations = iter + 1;
    // A 2D-only fix converges only with the height held.
    if (dx.norm() < opt.convergence_m && (hold_height || opt.fix_mode != SolverFixMode::k2DOnly)) {
      converged = true;
      break;
    }
  }

  if (!converged) return;

  // Residuals against the final estimate were computed in the last pass before the update;
  // the update is below the convergence threshold, so they stand.
  sol.p_ecef_m = p;
  bool reference_set = false;
  for (std::size_t g = 0; g < kClockGroups; ++g) {
    if (clock_column[g] == 0) continue;
    sol.group_clock_m[g] = clk[g];
    if (!reference_set) sol.clock_m = clk[g];
    reference_set = true;
  }
  const MatX n_inv = lu.inverse();
  sol.cov_ecef_m2 = n_inv.topLeftCorner<3, 3>();
  // Errors the satellites share (SolverOptions::iono_shared_*) correlate theirs; the weights
  // hold their variances only, so the position's covariance is the estimator's propagation
  // A C A^T, A = N^-1 H^T W, of the full covariance C = W^-1 + the shared errors' products
  // between different satellites, C_jk = l_j . l_k (l: a satellite's loading on the shared
  // errors, 1-sigma each; Teunissen, Adjustment Theory, 4.2 "propagation of covariances"):
  // (N^-1 + sum_jk a_j l_j . l_k a_k^T - sum_k |l_k|^2 a_k a_k^T) with a_k = N^-1 h_k / var_k.
  if (opt.klobuchar && (opt.iono_shared_scale_sigma > 0.0 || opt.iono_shared_gradient_sigma_m_per_deg > 0.0)) {
    const Geodetic g = geodetic_of(p);
    const double cos_lat = std::cos(g.lat_deg * kDegToRad);
    Mat3 al = Mat3::Zero();    // sum_k a_k l_k^T (position rows)
    Mat3 self = Mat3::Zero();  // sum_k |l_k|^2 a_k a_k^T
    for (std::size_t k = 0; k < n_sat_rows; ++k) {
      const Row& r = row_store[k];
      const RangeMeasurement& m = meas[r.index];
      const double l1_over_f = kGpsL1_Hz / m.carrier_hz;
      const PiercePoint ipp = iono_pierce_point(g, dirs[r.index]);
      const double grad_m = opt.iono_shared_gradient_sigma_m_per_deg * ipp.obliquity * l1_over_f * l1_over_f;
      const Vec3 l(opt.iono_shared_scale_sigma * sol.sats[r.index].iono_m, grad_m * ipp.dlat_deg,
                   grad_m * ipp.dlon_deg * cos_lat);
      const Vec3 a = (n_inv.topLeftCorner<3, 3>() * -r.u + n_inv.block<3, 1>(0, clock_column[r.group])) /
                     r.variance_m2;
      al.noalias() += a * l.transpose();
      self.noalias() += l.squaredNorm() * a * a.transpose();
    }
    sol.cov_ecef_m2 += al * al.transpose() - self;
  }
  sol.num_used = static_cast<int>(n_sat_rows);
  for (std::size_t k = 0; k < n_sat_rows; ++k)
    sol.chi_square += row_store[k].residual_m * row_store[k].residual_m / row_store[k].variance_m2;
  sol.degrees_of_freedom = static_cast<int>(n_sat_rows + (hold_height ? 1 : 0)) - static_cast<int>(lu.rows());
  sol.fix = hold_height ? FixType::k2D : FixType::k3D;
  std::array<Direction, kMaxSolverSatellites> used_dirs;
  for (std::size_t k = 0; k < n_sat_rows; ++k) used_dirs[k] = dirs[row_store[k].index];
  sol.dops = dops_from_directions(std::span<const Direction>(used_dirs.data(), n_sat_rows));

  // Velocity and clock drift from range rates (-lambda * Doppler), least squares. With the
  // satellite state rotated into the ECEF frame at reception (which accounts for the Earth's
  // rotation during the flight), the geometric range rate satisfies
  //   rr (1 + u.v_sat,inertial / c) = u.(R v_sat - v_rx),
  // the factor being the light-time derivative; the clocks add c (d(dt_rx)/dt - d(dt_sat)/dt).
  std::array<std::size_t, kMaxSolverSatellites> with_rate;
  std::size_t n_rate = 0;
  for (std::size_t k = 0; k < n_sat_rows; ++k)
    if (meas[row_store[k].index].range_rate_mps) with_rate[n_rate++] = row_store[k].index;
  if (n_rate >= 4) {
    MatN4 hv(static_cast<Eigen::Index>(n_rate), 4);
    VecN vv(static_cast<Eigen::Index>(n_rate));
    const Vec3 w(0.0, 0.0, kOmegaEarth_radps);
    // Weighted by the range rates' variances when every one has one (rows scaled by 1/sigma).
    bool weighted = true;
    for (std::size_t k = 0; k < n_rate; ++k) weighted = weighted && meas[with_rate[k]].range_rate_variance_m2ps2;
    for (std::size_t k = 0; k < n_rate; ++k) {
      const RangeMeasurement& m = meas[with_rate[k]];
      const double tau_s = (m.sat_p_ecef_m - p).norm() / kSpeedOfLight_mps;
      const Vec3 ps = rotate_earth(m.sat_p_ecef_m, tau_s);
      const Vec3 vs = rotate_earth(m.sat_v_ecef_mps, tau_s);
      const Vec3 u = (ps - p).normalized();
      const double light_time = 1.0 + u.dot(vs + w.cross(ps)) / kSpeedOfLight_mps;
      const auto r = static_cast<Eigen::Index>(k);
      const double scale = weighted ? 1.0 / std::sqrt(*m.range_rate_variance_m2ps2) : 1.0;
      hv.row(r) << -u.transpose() / light_time * scale, scale;
      vv(r) = (*m.range_rate_mps - (u.dot(vs) / light_time - m.sat_clock_drift_mps)) * scale;
    }
    const Eigen::Vector4d x = Eigen::ColPivHouseholderQR<MatN4>(hv).solve(vv);
    sol.v_ecef_mps = x.head<3>();
    sol.clock_drift_mps = x(3);
    if (weighted) {
      const Eigen::Matrix4d normal = hv.transpose() * hv;
      sol.cov_v_ecef_m2ps2 = normal.inverse().topLeftCorner<3, 3>();
    }
  }
}


// Regularised lower incomplete gamma function P(a, x): its series below x = a + 1, one minus
// the continued fraction of Q(a, x) above (Abramowitz & Stegun 6.5.29 and 6.5.31; the
// continued fraction evaluated by the modified Lentz method).
double gamma_p(double a, double x) {
  if (x <= 0.0) return 0.0;
  const double log_prefactor = -x + a * std::log(x) - std::lgamma(a);
  if (x < a + 1.0) {
    double term = 1.0 / a, sum = term;
    for (int n = 1; n < 500 && std::abs(term) > std::abs(sum) * 1e-16; ++n) {
      term *= x / (a + n);
      sum += term;
    }
    return sum * std::exp(log_prefactor);
  }
  constexpr double kTiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / kTiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 500; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < kTiny) d = kTiny;
    c = b + an / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < 1e-16) break;
  }
  return 1.0 - std::exp(log_prefactor) * h;
}

// The residual test's threshold for `dof` degrees of freedom, the quantiles of the usual
// probability computed once.
double raim_threshold(double p, int dof) {
  constexpr double kUsual = 0.999;
  static const std::array<double, kMaxSolverSatellites + 1> usual = [] {
    std::array<double, kMaxSolverSatellites + 1> q{};
    for (std::size_t k = 1; k < q.size(); ++k) q[k] = chi_square_quantile(kUsual, static_cast<int>(k));
    return q;
  }();
  return p == kUsual && dof < static_cast<int>(usual.size()) ? usual[static_cast<std::size_t>(dof)]
                                                             : chi_square_quantile(p, dof);
}

bool passes(const Solution& s, const SolverOptions& opt) {
  return s.fix != FixType::kNone &&
         (s.degrees_of_freedom <= 0 || s.chi_square <= raim_threshold(opt.raim_probability, s.degrees_of_freedom));
}
}  // namespace

double chi_square_quantile(double p, int dof) {
  const double a = 0.5 * dof;
  double lo = 0.0, hi = std::max(1.0, 2.0 * dof);
  while (gamma_p(a, 0.5 * hi) < p) hi *= 2.0;
  for (int i = 0; i < 200 && hi - lo > 1e-12 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (gamma_p(a, 0.5 * mid) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

SolverScratch::SolverScratch(std::size_t satellites) {
  kept.reserve(satellites);
  excluded.reserve(satellites);
  without.reserve(satellites);
  for (Solution* s : {&trial, &best, &current}) s->sats.reserve(satellites);
}

void solve(std::span<const RangeMeasurement> all, GpsTime t, const SolverOptions& opt,
           Solution& sol) {
  SolverScratch scratch;
  solve(all, t, opt, sol, scratch);
}

void solve(std::span<const RangeMeasurement> all, GpsTime t, const SolverOptions& opt,
           Solution& sol, SolverScratch& scratch) {
  solve_least_squares(all, t, opt, sol);
  if (!opt.raim || passes(sol, opt)) return;
  const std::span<const RangeMeasurement> meas =
      all.first(std::min(all.size(), kMaxSolverSatellites));
  // Fault detection failed (or there was no fix): exclusion, one satellite at a time (RTKLIB
  // raim_fde for the first): each satellite still in use left out in turn, the fix with the
  // smallest sum kept; it ends when that fix passes, and fails when none is left to test.
  std::vector<std::size_t>& kept = scratch.kept;  // indices into meas still in the solution
  kept.resize(meas.size());
  for (std::size_t i = 0; i < kept.size(); ++i) kept[i] = i;
  std::vector<std::size_t>& excluded = scratch.excluded;
  excluded.clear();
  std::vector<RangeMeasurement>& without = scratch.without;
  Solution& trial = scratch.trial;
  Solution& best = scratch.best;
  // `sol` keeps the failed fix over every satellite until an exclusion passes.
  Solution& current = scratch.current;  // the fix over `kept` (its sats in that order)
  current = sol;
  for (int round = 0; round < opt.raim_max_exclusions; ++round) {
    std::optional<std::size_t> out;  // position in kept of the best exclusion
    for (std::size_t k = 0; k < kept.size(); ++k) {
      if (current.fix != FixType::kNone && !current.sats[k].used) continue;  // below the mask
      without.clear();
      for (std::size_t j = 0; j < kept.size(); ++j)
        if (j != k) without.push_back(meas[kept[j]]);
      solve_least_squares(without, t, opt, trial);
      if (trial.fix != FixType::kNone && trial.degrees_of_freedom > 0 && (!out || trial.chi_square < best.chi_square)) {
        std::swap(best, trial);
        out = k;
      }
    }
    if (!out) break;
    excluded.push_back(kept[*out]);
    kept.erase(kept.begin() + static_cast<std::ptrdiff_t>(*out));
    if (!passes(best, opt)) {
      current = best;
      continue;
    }
    // The excluded satellites keep their places in sats, with their residuals against the fix.
    std::sort(excluded.begin(), excluded.end());
    for (const std::size_t i : excluded) {
      const RangeMeasurement& m = meas[i];
      SatResidual r = sol.sats[i];  // its direction and corrections, when computed
      r.sat = m.sat;
      const std::optional<double> clock = best.group_clock_m[clock_group(m.sat.system())];
      const double tau_s = (m.sat_p_ecef_m - best.p_ecef_m).norm() / kSpeedOfLight_mps;
      const double range = (rotate_earth(m.sat_p_ecef_m, tau_s) - best.p_ecef_m).norm();
      r.residual_m = clock ? m.pseudorange_m - (range + *clock - m.sat_clock_m + r.iono_m + r.tropo_m) : 0.0;
      r.used = false;
      r.excluded = true;
      best.sats.insert(best.sats.begin() + static_cast<std::ptrdiff_t>(i), r);
    }
    std::swap(sol, best);  // (both keep their storage)
    return;
  }
  sol.integrity_failed = sol.fix != FixType::kNone;  // a fix that failed, not too few satellites
  if (sol.integrity_failed && opt.raim_keeps_failed_fix) {
    if (sol.degrees_of_freedom > 0) sol.cov_ecef_m2 *= sol.chi_square / sol.degrees_of_freedom;
    return;
  }
  sol.fix = FixType::kNone;
}

}  // namespace navemu
