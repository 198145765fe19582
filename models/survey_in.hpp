#pragma once
// Survey-in of a base station's position (u-blox time mode "survey-in": F9 interface
// description, CFG-TMODE-MODE 1 and UBX-NAV-SVIN): the mean of the 3D fixes since the survey
// began, finished once it has lasted the minimum duration and the mean is accurate to the
// limit; the mean is then the base station's surveyed position.
//
// The accuracy of the mean. The fixes' errors are not white: the atmosphere and multipath
// change over minutes (models/measurement.hpp). For an error with autocorrelation
// s^2 exp(-|dt| / tau), the mean over a duration T >> tau has the variance 2 s^2 tau / T
// (the autocorrelation's integral, 2 s^2 tau, over T). So the mean is reported as accurate to
//   meanAcc = s_rms * sqrt(min(1, 2 tau / T)),
// s_rms the RMS of the fixes' own 3D accuracy estimates, however many fixes fell within T.

#include <cstdint>

#include "core/time.hpp"
#include "models/geodesy.hpp"

namespace navemu {

struct SurveyInParams {
  double min_duration_s = 0.0;        // CFG-TMODE-SVIN_MIN_DUR
  double acc_limit_m = 0.0;           // CFG-TMODE-SVIN_ACC_LIMIT
  double error_correlation_s = 60.0;  // tau: the multipath correlation time (models/measurement.hpp)
};

struct SurveyInState {
  bool active = false;      // in progress
  bool valid = false;       // finished: mean_ecef_m is the base position
  double duration_s = 0.0;  // from the first fix used to the last
  std::uint32_t obs = 0;    // fixes used
  Vec3 mean_ecef_m = Vec3::Zero();
  double mean_acc_m = 0.0;  // 3D, 1 sigma
};

class SurveyIn {
 public:
  // Begins a new survey (a receiver reset or a new time mode configuration does).
  void start(const SurveyInParams& p);
  // Time mode off or fixed: no survey.
  void stop() { state_ = {}; }
  // One 3D fix at t with its 3D 1-sigma accuracy estimate; ignored unless a survey is active.
  void add(GpsTime t, const Vec3& p_ecef_m, double sigma_3d_m);
  const SurveyInState& state() const { return state_; }

 private:
  SurveyInParams params_;
  SurveyInState state_;
  GpsTime first_;
  Vec3 origin_ecef_m_ = Vec3::Zero();  // the first fix: sums of differences keep the precision
  Vec3 sum_from_origin_m_ = Vec3::Zero();
  double sum_sigma2_m2_ = 0.0;
};

}  // namespace navemu
