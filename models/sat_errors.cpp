#include "models/sat_errors.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace navemu {

double paper_sv_ephemeris_error_m(double sat_lat_rad, double orbit_radius_m) {
  // Durst & Goodin section 2.1, implemented as printed:
  //   dR = sqrt((1 + sin(theta) / 2) 10^(2 R_ref / R_0) + c^2 1e-18 + 0.918).
  // With R_0 = R_ref the middle factor is 10^2 = 100, c^2 1e-18 = 0.0899, so the result is
  // sqrt(101.008) = 10.05 m at the equator and sqrt(151.008) = 12.29 m over the poles.
  constexpr double kRref_m = 26'550'000.0;
  const double c2 = kSpeedOfLight_mps * kSpeedOfLight_mps;
  const double v = (1.0 + 0.5 * std::sin(sat_lat_rad)) * std::pow(10.0, 2.0 * kRref_m / orbit_radius_m) +
                   c2 * 1e-18 + 0.918;
  return std::sqrt(v);
}

Mat3 R_rac_from_ecef(const Vec3& sat_p_ecef_m, const Vec3& sat_v_ecef_mps) {
  const Vec3 radial = sat_p_ecef_m.normalized();
  const Vec3 cross = sat_p_ecef_m.cross(sat_v_ecef_mps).normalized();
  const Vec3 along = cross.cross(radial);
  Mat3 r;
  r.row(0) = radial.transpose();
  r.row(1) = along.transpose();
  r.row(2) = cross.transpose();
  return r;
}

double sisre_relative_to_gps(GnssSystem system) {
  constexpr double kGps_m = 0.6;
  switch (system) {
    case GnssSystem::kGalileo: return 0.2 / kGps_m;
    case GnssSystem::kBeidou: return 1.0 / kGps_m;
    case GnssSystem::kGlonass: return 2.0 / kGps_m;
    default: return 1.0;
  }
}

SatErrors::SatErrors(const SatErrorParams& p, std::uint64_t seed) : p_(p), seed_(seed) {}

double SatErrors::range_error_m(SatId sat, double t_s, const Vec3& sat_p_ecef_m,
                                const Vec3& sat_v_ecef_mps, const Vec3& los_unit_ecef) {
  Sat* found = sats_.find(sat);
  const bool first = found == nullptr;
  if (first) {
    // One stream per satellite; the four processes draw from it in a fixed order (radial,
    // along, cross, clock) so a satellite's errors do not depend on which others were seen.
    RandomStream rng(seed_, stream_id("sat_errors", sat.stream_index()));
    const double k = sisre_relative_to_gps(sat.system());
    InterpolatedGaussMarkov radial(k * p_.radial_sigma_m, p_.tau_s, p_.knot_s, rng);
    InterpolatedGaussMarkov along(k * p_.along_sigma_m, p_.tau_s, p_.knot_s, rng);
    InterpolatedGaussMarkov cross(k * p_.cross_sigma_m, p_.tau_s, p_.knot_s, rng);
    InterpolatedGaussMarkov clock(k * p_.clock_sigma_m, p_.tau_s, p_.knot_s, rng);
    found = &sats_.try_emplace(sat, Sat{t_s, radial, along, cross, clock, rng}).first;
  }
  // The first call anchors the knots; a later time moves the processes on, an earlier or the
  // same one leaves them alone.
  Sat& s = *found;
  if (first || t_s > s.t_s) {
    for (InterpolatedGaussMarkov* x : {&s.radial, &s.along, &s.cross, &s.clock}) x->at(t_s, s.rng);
    s.t_s = t_s;
  }

  // Orbit error of the broadcast position (broadcast - true) in ECEF: the radial / along /
  // cross components on the frame's unit vectors (rows of R_rac_from_ecef).
  const Vec3 rac(s.radial.value(), s.along.value(), s.cross.value());
  const Vec3 dr_ecef = R_rac_from_ecef(sat_p_ecef_m, sat_v_ecef_mps).transpose() * rac;
  // The value to add to the pseudorange (sign convention in the header).
  return -dr_ecef.dot(los_unit_ecef) + s.clock.value();
}

SatErrors::Terms SatErrors::terms(SatId sat) const {
  const Sat* found = sats_.find(sat);
  if (found == nullptr) return {};
  const Sat& s = *found;
  return {s.radial.value(), s.along.value(), s.cross.value(), s.clock.value()};
}

double SatErrorParams::sisre_m() const {
  const double wr = 0.98, wac2 = 1.0 / 49.0;
  return std::sqrt(wr * wr * radial_sigma_m * radial_sigma_m + clock_sigma_m * clock_sigma_m +
                   wac2 * (along_sigma_m * along_sigma_m + cross_sigma_m * cross_sigma_m));
}

SatErrorParams SatErrorParams::scaled_to_sisre(double sisre) const {
  const double k = sisre / sisre_m();
  SatErrorParams p = *this;
  p.radial_sigma_m *= k;
  p.along_sigma_m *= k;
  p.cross_sigma_m *= k;
  p.clock_sigma_m *= k;
  return p;
}

}  // namespace navemu
