#pragma once
// Satellite position, velocity and clock from a GPS broadcast ephemeris
// (IS-GPS-200 20.3.3.4.3, Table 20-IV; satellite clock 20.3.3.3.3.1).

#include <array>

#include "models/ephemeris.hpp"
#include "models/geodesy.hpp"
#include "core/time.hpp"

namespace navemu {

struct SatState {
  Vec3 p_ecef_m = Vec3::Zero();    // in the ECEF frame at time t (the ephemeris' own frame)
  Vec3 v_ecef_mps = Vec3::Zero();  // velocity relative to the rotating ECEF frame
  double clock_bias_s = 0.0;       // af0 + af1 dt + af2 dt^2 + relativistic term (no TGD)
  double clock_drift_sps = 0.0;    // d(clock_bias)/dt
  double relativistic_s = 0.0;     // F e sqrt(A) sin(E)
};

// A state and the time it is of.
struct SatStateAt {
  GpsTime t;
  SatState state;
};

// State at GPS system time t (the satellite's transmit time).
SatState gps_sat_state(const GpsEphemeris& eph, GpsTime t);

// The constants of a system's broadcast orbit and clock: the gravitational constant, the
// Earth's rotation rate and the relativistic clock constant F = -2 sqrt(mu) / c^2.
struct KeplerConstants {
  double mu_m3ps2 = 0.0;
  double omega_earth_radps = 0.0;
  double relativistic_f = 0.0;  // s / sqrt(m)
};
KeplerConstants kepler_constants(GnssSystem system);
// BeiDou's geostationary satellites, whose broadcast orbit is computed in an inertial frame
// tilted by 5 degrees (BDS-SIS-ICD-B1I 3.0 5.2.4.12): C01-C05 and, from BDS-3, C59-C63.
bool is_beidou_geo(SatId sat);
// The state of any system's Keplerian broadcast ephemeris (GPS, QZSS, Galileo, BeiDou MEO/
// IGSO/GEO) at GPS time t, with the system's constants and time of week; for GPS the same as
// gps_sat_state. Galileo: OS SIS ICD 2.0 5.1.1; BeiDou: BDS-SIS-ICD-B1I 3.0 5.2.4.12
// (Table 5-11); QZSS: IS-QZSS-PNT, GPS's algorithm.
SatState broadcast_sat_state(const KeplerEphemeris& eph, GpsTime t);

// The state of a GLONASS satellite at GPS time t from its immediate data: the state vector at
// tb integrated to t (GLONASS ICD edition 5.1 A.3.1.2, fourth-order Runge-Kutta in steps of at
// most 60 s, the lunisolar accelerations held), in PZ-90.11, which agrees with the ITRF and
// WGS 84 to centimetres. Clock: the satellite's offset from GLONASS time, -tau_n + gamma_n
// (t - tb) (ICD 3.3.3; relativity included by the ground segment); GLONASS time's own offset
// from GPS time is the receiver's to estimate.
SatState glonass_sat_state(const GlonassEphemeris& eph, GpsTime t);
// That clock alone, -tau_n + gamma_n (t - tb) (to turn the satellite's time into GPS time).
double glonass_sat_clock_s(const GlonassEphemeris& eph, GpsTime t);

// One GLONASS record's states on a 60 s grid from tb - 16 min to tb + 16 min, each the Runge-Kutta
// integration from tb in 60 s steps (A.3.1.2), computed once: a state at t is then one step
// from the nearest node (|t - node| <= 30 s) instead of up to 16 from tb, within 0.2 mm of
// glonass_sat_state (tests/models/test_orbit_multi_gnss.cpp). Beyond the grid: glonass_sat_state.
// For a receiver that evaluates the same record at every epoch; no allocation.
class GlonassArc {
 public:
  GlonassArc() = default;
  explicit GlonassArc(const GlonassEphemeris& eph);
  // Whether the arc was made for this record (at this address, with these data: storage that
  // is reused for another record does not pass).
  bool of(const GlonassEphemeris& eph) const {
    return eph_ == &eph && tb_ == eph.tb && p_[kHalfNodes] == eph.p_pz90_m && v_[kHalfNodes] == eph.v_pz90_mps &&
           a_ls_ == eph.a_pz90_mps2;
  }
  SatState state(GpsTime t) const;

 private:
  static constexpr int kHalfNodes = 16;
  static constexpr double kNodeStep_s = 60.0;
  const GlonassEphemeris* eph_ = nullptr;
  GpsTime tb_;
  Vec3 a_ls_ = Vec3::Zero();
  std::array<Vec3, 2 * kHalfNodes + 1> p_{}, v_{};
};

// Satellite clock polynomial only (no relativistic term), used to turn the satellite's own
// time into GPS system time (IS-GPS-200 20.3.3.3.3.1).
double gps_sat_clock_poly_s(const KeplerEphemeris& eph, GpsTime t);

// The data set a satellite would get in a new upload with reference time `toe`, when its orbit
// and clock go on as `eph` describes them: the same Keplerian orbit and clock polynomial
// parametrised at the new toe (IS-GPS-200 Table 20-IV: M0 advanced by n dt, Omega0 so that the
// node's longitude is unchanged at every time, i0 by IDOT dt; Table 20-III clock: af0, af1 at
// the new toc), so the two agree in position and clock at every time. toe and toc move by
// the same whole number of 2 h uploads k; IODE and the 8 LSBs of IODC go up by k (mod 256) and
// the transmission time keeps its offset from toe.
GpsEphemeris reuploaded(const GpsEphemeris& eph, GpsTime toe);

// The same for GLONASS, whose uploads are state vectors: the next record's state is this one's
// integrated to `tb` (glonass_sat_state), its clock offset -tau_n + gamma_n (tb - tb_old) and
// its frame time moved on, so the two agree to the integration's error at every time.
GlonassEphemeris reuploaded(const GlonassEphemeris& eph, GpsTime tb);

// Rotation of an ECEF vector by the Earth's rotation during `dt_s` (the Sagnac correction):
// a vector fixed in inertial space, expressed in the ECEF frame at t, expressed in the ECEF
// frame at t + dt_s.
Vec3 rotate_earth(const Vec3& v_ecef, double dt_s);

// Geometry of one satellite seen by a receiver at a reception time.
struct SatGeometry {
  GpsTime t_transmit;            // GPS system time of transmission
  double flight_time_s = 0.0;    // t_receive - t_transmit before rounding to the nanosecond
  SatState sat;                  // state at t_transmit, rotated into the ECEF frame at reception
  SatState sat_transmit;         // the same in the ECEF frame at t_transmit (the ephemeris' own)
  double range_m = 0.0;          // |p_sat - p_rx| in the reception frame (includes Sagnac)
  double range_rate_mps = 0.0;   // d(range)/dt seen by the receiver
  AzEl dir;                      // azimuth/elevation on the geodetic normal
  Direction direction;           // dir with its sines and cosines
};

// The receiver as every satellite's geometry needs it, computed once per epoch.
struct ReceiverPlace {
  Vec3 p_ecef_m = Vec3::Zero();
  Vec3 v_ecef_mps = Vec3::Zero();
  Mat3 R_enu_from_ecef = Mat3::Identity();
};
ReceiverPlace receiver_place(const Vec3& p_rx_ecef_m, const Vec3& v_rx_ecef_mps = Vec3::Zero());

// Light-time iteration: finds the transmit time t_tx with |p_sat(t_tx) rotated to the frame
// at t_rx - p_rx| = c (t_rx - t_tx), then evaluates the geometry. `tau_guess_s`: where the
// iteration starts (the flight time of the satellite's previous epoch saves an evaluation).
SatGeometry gps_sat_geometry(const GpsEphemeris& eph, GpsTime t_receive, const ReceiverPlace& rx,
                             double tau_guess_s = 0.075);
// The same for a record of any system (broadcast_sat_state, glonass_sat_state); `r` must hold
// a record. `arc`: the GLONASS record's arc when the caller keeps one (GlonassArc).
SatState record_sat_state(const BroadcastRecord& r, GpsTime t);
SatGeometry sat_geometry(const BroadcastRecord& r, GpsTime t_receive, const ReceiverPlace& rx,
                         double tau_guess_s = 0.075, const GlonassArc* arc = nullptr);
SatGeometry gps_sat_geometry(const GpsEphemeris& eph, GpsTime t_receive, const Vec3& p_rx_ecef_m,
                             const Vec3& v_rx_ecef_mps = Vec3::Zero());

}  // namespace navemu
