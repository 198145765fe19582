#pragma once
// The emulated GNSS receiver: the measurement generator (models/measurement.hpp) and the
// position engine (models/solver.hpp) at the receiver's epochs, with the bookkeeping a
// receiver reports: fix type, satellites in view and used, DOPs and accuracy estimates.
// Time is passed in; nothing here reads a clock or does I/O.

#include <array>
#include <limits>
#include <optional>
#include <vector>

#include "models/geoid.hpp"
#include "models/imu_kinematics.hpp"
#include "models/measurement.hpp"
#include "models/random.hpp"
#include "models/solver.hpp"

namespace navemu {

struct ReceiverParams {
  MeasurementConfig measurement;
  int max_channels = 12;  // the highest satellites tracked at most
  // The paper's low-fidelity receiver (sect. 4): the fix is the truth plus white noise of this
  // 1-sigma per axis (north, east, down), whatever the satellites do; DOPs and the satellites
  // are still reported. Unset: the position engine's solution.
  std::optional<double> ideal_sigma_m;
  // The geoid of the heights above mean sea level the receiver reports (it must outlive the
  // receiver); none: geoid separation 0, MSL heights equal ellipsoidal heights.
  const GeoidGrid* geoid = nullptr;
};

// The position engine's settings a client may change while running (u-blox CFG-NAVSPG-* and
// CFG-NAV5; ZED-F9P integration manual UBX-18010802, 3.1.7 "Navigation configuration"): which
// satellites it uses, when it attempts a fix, which fixes it reports.
struct NavEngineSettings {
  double elevation_mask_deg = 5.0;  // satellites lower are not used
  double min_cn0_dbhz = 0.0;        // satellites weaker (L1) are not used
  // A fix is attempted only with at least cn0_threshold_sats satellites at cn0_threshold_dbhz
  // or stronger (0: always).
  int cn0_threshold_sats = 0;
  double cn0_threshold_dbhz = 0.0;
  SolverFixMode fix_mode = SolverFixMode::kAuto;
  double fixed_height_msl_m = 0.0;  // the height 2D-only fixes hold, above mean sea level
  // The dynamic platform model's sanity limits: a fix beyond one is invalid (no fix).
  double max_height_msl_m = std::numeric_limits<double>::infinity();
  double max_h_speed_mps = std::numeric_limits<double>::infinity();
  double max_v_speed_mps = std::numeric_limits<double>::infinity();
  bool zero_velocity = false;  // a stationary platform: velocity reported as 0
  // The systems whose signals the receiver tracks (system_bit; u-blox CFG-SIGNAL-*_ENA): the
  // others' satellites are dropped and re-acquired when enabled again.
  std::uint32_t systems = ~0u;
  // Of those, the systems whose second-band signal is enabled (CFG-SIGNAL-*_L2*_ENA, E5B, B2),
  // for profiles with that band.
  std::uint32_t l2_systems = ~0u;
};

struct ReceiverSatellite {
  SatId sat;
  double az_deg = 0.0, el_deg = 0.0, cn0_dbhz = 0.0;  // C/N0 of the L1 signal
  bool used = false;
  bool unhealthy = false;   // flagged so by its broadcast data: tracked, not used
  double residual_m = 0.0;  // pseudorange residual of the fix (used satellites), else 0
  std::array<double, 3> band_cn0_dbhz{};  // of each Band's signal; 0: not tracked on it
  bool smoothed = false;  // used with a carrier-smoothed pseudorange (past its arc's first epoch)
};

struct ReceiverFix {
  GpsTime t;  // the navigation epoch, GPS time (the nominal one: a whole period)
  // GPS time of the receiver's clock tick that took the epoch minus t: within +-0.5 ms, the
  // remainder of its clock bias (models/measurement.cpp; UBX NAV-PVT nano, NAV-SOL fTOW).
  double time_offset_s = 0.0;
  FixType fix = FixType::kNone;
  Geodetic position;
  Vec3 p_ecef_m = Vec3::Zero();
  std::optional<Vec3> v_ned_mps;
  Dops dops;
  int num_used = 0;
  std::vector<ReceiverSatellite> satellites;  // tracked, by SatId
  // 1-sigma accuracy estimates from the solution's covariance (models/solver.hpp), north, east,
  // horizontal (root sum of squares) and vertical.
  double sigma_n_m = 0.0, sigma_e_m = 0.0, sigma_h_m = 0.0, sigma_v_m = 0.0;
  double range_rms_m = 0.0;                   // RMS of the used pseudorange residuals
  // 1-sigma of the velocity from its covariance (models/solver.hpp), 3D and horizontal (root
  // sums of squares); 0 without a velocity covariance.
  double sigma_speed_mps = 0.0, sigma_h_speed_mps = 0.0;
  // Geoid undulation N at the fix (ReceiverParams::geoid): the height above mean sea level is
  // position.h_m - geoid_separation_m. 0 without a fix or a geoid.
  double geoid_separation_m = 0.0;
};

class Receiver {
 public:
  // `nav` must outlive the receiver (a temporary does not compile).
  Receiver(const NavData& nav, const ReceiverParams& p);
  Receiver(NavData&&, const ReceiverParams&) = delete;
  // The fix at epoch t for a receiver at `truth` (position and velocity); without truth (its
  // stream was lost) the receiver reports no fix and keeps no satellites. The reference stays
  // valid until the next update; the receiver reuses its storage, so a steady run allocates
  // nothing per epoch.
  const ReceiverFix& update(GpsTime t, const ImuTruth* truth);
  const ReceiverParams& params() const { return p_; }
  // Applies from the next update. Until set: the elevation mask of ReceiverParams, no other
  // filter or limit.
  void set_engine(const NavEngineSettings& s) { engine_ = s; }
  const NavEngineSettings& engine() const { return engine_; }
  // The raw measurements of the last update (tracked satellites), for raw-data output.
  const EpochMeasurements& measurements() const { return meas_; }
  // The scenario's start, from which scheduled events count (MeasurementGenerator).
  void set_event_origin(GpsTime start) { gen_.set_event_origin(start); }
  void add_events(const GnssEvents& e) { gen_.add_events(e); }
  void clear_events() { gen_.clear_events(); }

 private:
  ReceiverParams p_;
  NavEngineSettings engine_;
  MeasurementGenerator gen_;
  std::optional<GpsTime> last_t_;
  Vec3 last_fix_ecef_m_ = Vec3::Zero();
  EpochMeasurements meas_;
  std::vector<RangeMeasurement> solver_input_;
  Solution solution_;
  SolverScratch solver_scratch_{kMaxSolverSatellites};
  ReceiverFix fix_;
  RandomStream ideal_rng_;
};

}  // namespace navemu
