#pragma once
// The receiver's surroundings from the run configuration (gnss.scene): the OBJ mesh and
// material table loaded, the ray-tracing scene built, and the signal-environment model the
// measurement generator asks per satellite (models/signal_environment.hpp).

#include <iosfwd>
#include <memory>

#include "emulator/run_config.hpp"
#include "models/signal_environment.hpp"
#include "models/tracking.hpp"

namespace navemu {

// Loads and builds; says on `log` what was built and how long it took. Bad input throws
// InputError naming the file and line.
std::shared_ptr<const SignalEnvironmentModel> make_scene_environment(
    const SceneSpec& spec, const Geodetic& default_origin, const TrackingParams& tracking,
    const AntennaPattern& antenna, std::ostream& log);

}  // namespace navemu
