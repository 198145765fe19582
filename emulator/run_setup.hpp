#pragma once
// A run's configuration turned into sensor channels, in three steps:
//   resolve_run   every file read and every parameter built and checked (profiles, receiver
//                 classes and antenna, navigation file, scene, geoid, IMU rates): nothing reads
//                 a file once the run has started;
//   open_outputs  the ports, CAN outputs and recorders, opened before the start is known (so
//                 clients can attach while lockstep waits for its first datagram);
//   make_channels the channels, once the scenario's start is known (the built-in constellation
//                 is generated around it, navigation data checked against it).

#include <iosfwd>
#include <memory>
#include <optional>
#include <vector>

#include "emulator/control.hpp"
#include "emulator/engine.hpp"
#include "emulator/gnss_channel.hpp"
#include "emulator/imu_can.hpp"
#include "emulator/recorders.hpp"
#include "emulator/run_config.hpp"
#include "emulator/truth_source.hpp"
#include "models/ephemeris.hpp"
#include "models/imu_model.hpp"
#include "models/receiver.hpp"

namespace navemu {

struct GnssPlan {
  ReceiverParams receiver;
  std::optional<NavData> nav_file;  // the RINEX file's records; none: the built-in constellation
};

struct ImuPlan {
  ImuParams params;
  IdealImu initial;  // held until the first truth (a level IMU at rest at truth.position)
};

struct RunPlan {
  std::optional<GnssPlan> gnss;
  std::optional<ImuPlan> imu;
};

// InputError naming the file and key for anything that does not load or check.
RunPlan resolve_run(const RunConfig& cfg, const EngineOptions& opt, std::ostream& log);

struct RunOutputs {
  GnssPorts gnss;  // offline: nmea.log or ubx.bin
  std::unique_ptr<ControlPort> control;  // live control (emulator/control.hpp); none: off
  std::unique_ptr<ImuCanOutputs> can;  // offline: can.log
  std::vector<std::unique_ptr<EpochRecorder>> epoch_recorders;    // offline: truth.csv, gnss.csv
  std::vector<std::unique_ptr<SampleRecorder>> sample_recorders;  // imu.csv, or the live imu.log
};

// Opens them. Offline the output folder is created and emptied of the streams this run may
// write.
RunOutputs open_outputs(const RunConfig& cfg, const RunPlan& plan, const EngineOptions& opt,
                        std::ostream& log);
// Start-up lines: where each output is.
void print_outputs(const RunConfig& cfg, const RunPlan& plan, const RunOutputs& outputs,
                   const EngineOptions& opt, std::ostream& log);

// The navigation data of a run that starts at `start`: the file's, or the built-in
// constellation around `start`; InputError unless it covers the scenario.
NavData scenario_nav(const RunPlan& plan, GpsTime start, const EngineOptions& opt, std::ostream& log);

// The channels, in the order their events run at equal times (GNSS, IMU, then live control),
// taking over the outputs; `nav`: scenario_nav()'s (unused without GNSS); `truth`: the run's
// truth, when it takes faults (live control acts on it). Start-up lines on `log`.
std::vector<std::unique_ptr<SensorChannel>> make_channels(const RunConfig& cfg, const RunPlan& plan,
                                                          RunOutputs& outputs, NavData nav,
                                                          const EngineOptions& opt, ImpairedTruth* truth,
                                                          std::ostream& log);

}  // namespace navemu
