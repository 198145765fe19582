#pragma once
// The signal environment of one satellite at one instant: whether its signal reaches the
// antenna, and the code, carrier and power errors the receiver's tracking loops make of the
// composite of all paths. The measurement generator (models/measurement.hpp) asks this for
// every satellite above the horizon when a scene is configured; the statistical multipath
// model is off then.

#include <memory>
#include <vector>

#include "models/geodesy.hpp"
#include "models/multipath.hpp"
#include "models/scene.hpp"

namespace navemu {

struct SignalEnvironment {
  bool received = true;      // some path carries signal (false: blocked, nothing to track)
  bool nlos = false;         // no direct path: tracked on reflections only
  double code_error_m = 0.0;   // pseudorange error of the composite signal
  double phase_error_m = 0.0;  // carrier-phase error of the composite signal
  double power_db = 0.0;       // composite power relative to the unobstructed direct signal
  int reflections = 0;         // reflected paths found
};

class SignalEnvironmentModel {
 public:
  virtual ~SignalEnvironmentModel() = default;
  // p_rx_ecef_m: the antenna; u_ecef: unit vector from the antenna towards the satellite.
  virtual SignalEnvironment evaluate(const Vec3& p_rx_ecef_m, const Vec3& u_ecef) const = 0;
};

enum class MultipathResponse {
  kDiscriminator,  // early-minus-late DLL on the composite signal (default)
  kPaperRule,      // the paper's first-return rule with a cut-off (models/multipath.hpp)
};

struct SceneEnvironmentParams {
  Geodetic origin;                   // the scene's ENU origin
  Vec3 offset_enu_m = Vec3::Zero();  // the mesh's (0,0,0) relative to the origin
  ScenePathOptions paths;
  MultipathResponse response = MultipathResponse::kDiscriminator;
  double chip_spacing = 1.0;         // early-late spacing, chips
  double cutoff_m = 45.0;            // paper rule: 150 ns
  AntennaPattern antenna = patch_antenna_pattern();
};

// Paths through a scene (models/scene.hpp), each reflected path weighted by its reflection
// coefficient and the antenna's gain for its arrival direction and polarisation:
//   a_i = [Gamma_co G_rhcp(el_i) + Gamma_cross G_lhcp(el_i)] / G_rhcp(el_sat) * foliage_i
//         * exp(-j 2 pi excess_i / lambda)
// (amplitude gains: 10^(dB/20)), the direct path a_0 = foliage_0 (0 when blocked), both
// relative to the unobstructed direct signal whose antenna gain the C/N0 model already holds.
// Fixed-loss materials use a real coefficient -10^(-loss/20) in the co-polar part.
class SceneEnvironment final : public SignalEnvironmentModel {
 public:
  SceneEnvironment(std::shared_ptr<const Scene> scene, SceneEnvironmentParams params);
  SignalEnvironment evaluate(const Vec3& p_rx_ecef_m, const Vec3& u_ecef) const override;
  // The signal paths of one evaluation (for tests and diagnostics).
  std::vector<PathSignal> paths(const Vec3& p_rx_ecef_m, const Vec3& u_ecef) const;

 private:
  std::shared_ptr<const Scene> scene_;
  SceneEnvironmentParams p_;
  Mat3 R_enu_from_ecef_;
};

}  // namespace navemu
