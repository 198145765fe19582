#include "models/survey_in.hpp"

#include <algorithm>
#include <cmath>

namespace navemu {

void SurveyIn::start(const SurveyInParams& p) {
  *this = SurveyIn{};
  params_ = p;
  state_.active = true;
}

void SurveyIn::add(GpsTime t, const Vec3& p_ecef_m, double sigma_3d_m) {
  if (!state_.active) return;
  if (state_.obs == 0) {
    first_ = t;
    origin_ecef_m_ = p_ecef_m;
  }
  ++state_.obs;
  sum_from_origin_m_ += p_ecef_m - origin_ecef_m_;
  sum_sigma2_m2_ += sigma_3d_m * sigma_3d_m;
  const double n = static_cast<double>(state_.obs);
  state_.duration_s = seconds_between(t, first_);
  state_.mean_ecef_m = origin_ecef_m_ + sum_from_origin_m_ / n;
  const double correlated =
      state_.duration_s > 0.0 ? std::min(1.0, 2.0 * params_.error_correlation_s / state_.duration_s) : 1.0;
  state_.mean_acc_m = std::sqrt(sum_sigma2_m2_ / n * correlated);
  if (state_.duration_s >= params_.min_duration_s && state_.mean_acc_m <= params_.acc_limit_m) {
    state_.active = false;
    state_.valid = true;
  }
}

}  // namespace navemu
