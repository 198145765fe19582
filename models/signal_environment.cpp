#include "models/signal_environment.hpp"

#include <cmath>
#include <complex>

namespace navemu {

namespace {

double amplitude_of_db(double db) { return std::pow(10.0, db / 20.0); }

}  // namespace

SceneEnvironment::SceneEnvironment(std::shared_ptr<const Scene> scene, SceneEnvironmentParams params)
    : scene_(std::move(scene)), p_(std::move(params)), R_enu_from_ecef_(R_enu_from_ecef(p_.origin)) {}

std::vector<PathSignal> SceneEnvironment::paths(const Vec3& p_rx_ecef_m, const Vec3& u_ecef) const {
  const Vec3 p_enu = enu_from_ecef(p_rx_ecef_m, p_.origin) - p_.offset_enu_m;
  const Vec3 u_enu = (R_enu_from_ecef_ * u_ecef).normalized();
  std::vector<PathSignal> out;
  const DirectPath d = scene_->direct(p_enu, u_enu);
  if (!d.blocked) out.push_back({0.0, {amplitude_of_db(-d.foliage_loss_db), 0.0}});

  thread_local std::vector<ReflectedPath> reflected;
  scene_->reflections(p_enu, u_enu, p_.paths, reflected);
  const double el_sat = std::asin(std::clamp(u_enu.z(), -1.0, 1.0));
  const double g_direct = amplitude_of_db(antenna_gain_db(p_.antenna, el_sat, false));
  for (const ReflectedPath& r : reflected) {
    // The wave's polarisation after each reflection: co-polar keeps RHCP, cross-polar turns it
    // into LHCP; two reflections combine (co co + cross cross stays RHCP).
    std::complex<double> rhcp{1.0, 0.0}, lhcp{0.0, 0.0};
    for (int k = 0; k < r.order; ++k) {
      const SceneMaterial& m = scene_->material(r.material[static_cast<std::size_t>(k)]);
      Fresnel f;
      if (m.perfect_conductor) {
        f = fresnel_perfect_conductor();
      } else if (m.reflection_loss_db >= 0.0) {
        f.co = -amplitude_of_db(-m.reflection_loss_db);
        f.cross = 0.0;
      } else {
        f = fresnel(m.relative_permittivity, m.conductivity_spm, r.grazing_rad[static_cast<std::size_t>(k)]);
      }
      const std::complex<double> new_rhcp = f.co * rhcp + f.cross * lhcp;
      const std::complex<double> new_lhcp = f.cross * rhcp + f.co * lhcp;
      rhcp = new_rhcp;
      lhcp = new_lhcp;
    }
    const double el_arrival = std::asin(std::clamp(r.arrival_enu.z(), -1.0, 1.0));
    const std::complex<double> gain =
        rhcp * amplitude_of_db(antenna_gain_db(p_.antenna, el_arrival, false)) +
        lhcp * amplitude_of_db(antenna_gain_db(p_.antenna, el_arrival, true));
    const double phase = -2.0 * M_PI * r.excess_m / kL1WavelengthM;
    const std::complex<double> a =
        gain / g_direct * amplitude_of_db(-r.foliage_loss_db) * std::polar(1.0, phase);
    out.push_back({r.excess_m, a});
  }
  return out;
}

SignalEnvironment SceneEnvironment::evaluate(const Vec3& p_rx_ecef_m, const Vec3& u_ecef) const {
  const std::vector<PathSignal> paths = this->paths(p_rx_ecef_m, u_ecef);
  SignalEnvironment e;
  e.nlos = paths.empty() || paths.front().delay_m != 0.0;
  e.reflections = static_cast<int>(paths.size()) - (e.nlos ? 0 : 1);
  std::optional<double> code;
  if (p_.response == MultipathResponse::kPaperRule) {
    code = paper_rule_delay_m(paths, p_.cutoff_m);
  } else {
    code = eml_tracking_error_m(paths, p_.chip_spacing);
  }
  if (!code) {
    e.received = false;
    e.power_db = -200.0;
    return e;
  }
  e.code_error_m = *code;
  e.power_db = composite_power_db(paths, *code);
  e.phase_error_m = composite_phase_error_m(paths, *code);
  return e;
}

}  // namespace navemu
