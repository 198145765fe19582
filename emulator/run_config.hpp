#pragma once
// The configuration of `navemu run` and `navemu simulate` (configs/default.yaml documents every
// key) and the GNSS receiver profiles of configs/gnss/. Loaded and validated once, converted to
// plain structs; every problem is an InputError "<file>:<line>: <section.key>: <problem>".

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "models/geodesy.hpp"
#include "models/imu_model.hpp"
#include "models/measurement.hpp"
#include "models/trajectory.hpp"

namespace navemu {

// A u-blox receiver's identity and defaults (configs/gnss/ublox-*.yaml, key `ubx`).
struct UbxSettings {
  std::string protver;  // "18.00": MON-VER's PROTVER=, and whether CFG-VALSET/VALGET exist (>= 27)
  std::string sw_version, hw_version;
  std::vector<std::string> extensions;
  // UBX messages output by default ("NAV-PVT") with their rate (every n-th solution).
  std::vector<std::pair<std::string, int>> messages;
  bool nmea_out = true;  // NMEA in the port's output protocol mask at start
};

// A GNSS receiver's wire behaviour: what it sends, how often, in which style.
struct GnssProfile {
  std::string name;  // the file's stem
  std::filesystem::path file;
  std::string description;
  double rate_hz = 1.0;          // navigation epochs per second
  double output_latency_s = 0.0;  // from the measurement epoch to the first byte out
  int baud = 9600;               // of a serial output
  // The systems tracked (system_bit), YAML `systems: [GPS, GLONASS, Galileo, BeiDou, QZSS]`.
  std::uint32_t systems = system_bit(GnssSystem::kGps);
  // The bands tracked (band_bit), YAML `bands: [L1, L2]` or `[L1, L5]`: the signal of each
  // system on each (models/measurement.hpp band_signal). L1 alone when not given.
  std::uint32_t bands = band_bit(Band::kL1);
  // Main NMEA talker (GGA, RMC, GSA, ...); unset in the YAML: the systems' own, GN for several
  // (nmea_main_talker).
  std::string talker = "GP";
  std::string style = "ublox";   // NMEA field widths: ublox or garmin
  std::optional<int> time_decimals;  // decimals of the UTC seconds; unset: the style's
  // Sentences in output order, each with its divisor (sent every n-th epoch).
  std::vector<std::pair<std::string, int>> sentences;
  ReceiverClass receiver_class = ReceiverClass::kConsumer;
  double elevation_mask_deg = 5.0;
  int max_channels = 12;  // satellites tracked at most (the highest)
  // Antenna: RHCP gain (dB relative to the zenith) by elevation (deg), held beyond its ends,
  // for C/N0 and for reflected signals arriving from below; empty: a typical patch
  // (models/tracking.hpp). LHCP rejection applies to cross-polar reflections.
  std::vector<std::pair<double, double>> antenna_gain_db_by_el_deg;
  double antenna_lhcp_rejection_db = 15.0;
  // The receiver clock (models/receiver_clock.hpp); YAML `clock: {initial_bias_max_ms,
  // frequency_offset_sigma_ppb}` draws its start-up state: a bias uniform in +-max and a
  // free-running oscillator's frequency offset. Unset: an ideal start (no bias, no offset).
  ReceiverClockParams clock;
  std::optional<UbxSettings> ubx;  // a u-blox receiver: UBX output and configuration
  // The position engine's carrier smoothing of the code, s (MeasurementConfig::
  // carrier_smoothing_s); YAML `carrier_smoothing_s`, 0 or unset: raw code.
  double carrier_smoothing_s = 0.0;
};

// The sentence names a profile may list, and the UBX messages a u-blox profile may output.
const std::vector<std::string>& known_nmea_sentences();
const std::vector<std::string>& known_ubx_outputs();

std::vector<std::string> available_gnss_profiles();  // names in configs/gnss, sorted
GnssProfile load_gnss_profile(const std::string& name_or_path);

// Where a byte stream goes.
struct OutputSpec {
  std::string type;  // pty | serial | tcp | udp | file
  std::string link;  // pty: symlink path (optional)
  std::string device;  // serial
  int baud = 0;        // serial; 0: the profile's
  std::string address = "127.0.0.1";  // tcp bind / udp destination
  int port = 0;
  std::string path;  // file
  std::size_t max_backlog_bytes = 4096;  // pty
  std::string gpsd_socket;  // pty: gpsd's control socket, told when the pty comes and goes
  // The receiver's port it stands for: i2c, uart1, uart2, usb, spi (YAML `port` on pty, serial
  // and file outputs, `receiver_port` on tcp and udp ones, whose `port` is the network's).
  std::string receiver_port = "uart1";
};

// How IMU samples become CAN frames (protocols/can_frames.hpp, configs/can/navemu.dbc).
enum class CanLayout {
  kJ1939,      // SAE J1939-71 ARI + ACCS, two 8-byte frames per sample
  kHighRes,    // navemu high resolution, five classic frames per sample
  kHighResFd,  // navemu high resolution, one 64-byte CAN FD frame per sample
};
const char* can_layout_name(CanLayout layout);

// Where CAN frames go.
struct CanOutputSpec {
  std::string type;            // socketcan | slcan | candump
  std::string interface;       // socketcan: vcan0, can0; candump: the log's interface column
  std::string link;            // slcan over a pty: symlink path (optional)
  std::string device;          // slcan over a serial device (instead of a pty)
  int baud = 115200;           // slcan serial
  bool auto_open = false;      // slcan: send without waiting for the client's "O"
  std::string path;            // candump
  std::vector<CanLayout> layouts{CanLayout::kJ1939};
  // socketcan: where the frames go instead when the interface cannot be opened (no kernel
  // CAN, no such interface); empty: that is an error. Takes this output's layouts.
  std::vector<CanOutputSpec> fallback;
};

struct CanSettings {
  std::uint8_t priority = 3;          // J1939 identifier priority 0..7
  std::uint8_t source_address = 0x80;  // J1939 source address 0..253
  std::uint32_t base_id = 0x500;      // high-resolution layout's first identifier
  bool extended = false;              // high-resolution layout with 29-bit identifiers
};

// A 3D scene around the receiver (gnss.scene): visibility and multipath by ray tracing.
struct SceneSpec {
  std::string obj;        // Wavefront OBJ; empty: open sky
  std::string materials;  // YAML material table (configs/scenes/materials.yaml by default)
  std::optional<Geodetic> origin;  // the mesh's ENU origin; unset: truth.position
  Vec3 offset_enu_m = Vec3::Zero();
  int max_order = 1;               // reflections: 0, 1 or 2
  double max_range_m = 300.0;      // reflection points farther from the antenna are ignored
  std::string response = "discriminator";  // discriminator | paper
  double cutoff_m = 45.0;          // paper rule: delay difference the correlator cannot resolve
  std::optional<double> chip_spacing;  // early-late spacing, chips; unset: the receiver class's
};

enum class TimeMode { kRealTime, kLockstep };
enum class TruthSourceKind { kStationary, kCircle, kLine, kWaypoints, kCsv, kUdp };

struct TruthSpec {
  TruthSourceKind kind = TruthSourceKind::kCircle;
  Geodetic position{32.3, -90.9, 60.0};  // stationary point, circle centre, line start
  double yaw_deg = 0.0;
  CircleTrajectory circle;
  LineTrajectory line;
  WaypointTrajectory waypoints;
  std::string csv_path;  // "-" : standard input
  std::string udp_address = "127.0.0.1";
  int udp_port = 5555;
  double timeout_s = 1.0;       // streamed truth: extrapolated this long, then lost
  double max_jump_s = 5.0;      // a sample further ahead is an outlier (emulator/truth_buffer.hpp)
  int resync_samples = 3;       // consecutive consistent outliers that re-synchronise the stream
  double first_wait_s = 120.0;  // lockstep: longest wait for the first datagram; 0: no limit
};

// The live control port (`control:`, emulator/control.hpp): TCP on this address.
struct ControlSpec {
  std::string address = "127.0.0.1";
  int port = 0;  // 0: any free port (navemu prints it)
};

// Truth impairments (`events:` type truth, issue "impairments" deliverable 4): what a faulty
// simulator feeds the sensors, for testing a stack's own guards (emulator/truth_source.hpp
// impaired_truth). Each acts while its window lasts:
//  - freeze: the state stays what it was at the window's start (position, velocity, attitude,
//    specific force and rates), as a simulator that keeps sending its last sample;
//  - teleport: the position offset_enu_m (east, north, up) away, velocity, attitude, specific
//    force and rates unchanged: a jump no motion explains;
//  - time jump: the state of jump_s later (earlier when negative), as a simulator whose clock
//    stepped.
enum class TruthFaultKind : std::uint8_t { kFreeze, kTeleport, kTimeJump };
struct TruthFault {
  EventWindow window;
  TruthFaultKind kind = TruthFaultKind::kFreeze;
  Vec3 offset_enu_m = Vec3::Zero();  // kTeleport
  double jump_s = 0.0;               // kTimeJump
};

struct RunConfig {
  std::filesystem::path file;
  std::string description;  // one line for `navemu profiles`
  std::string start = "now";
  TimeMode time_mode = TimeMode::kRealTime;
  std::uint64_t seed = 1;
  std::string nav_file;  // empty: built-in constellation
  double status_interval_s = 1.0;  // 0: no status line

  TruthSpec truth;

  bool gnss_enabled = true;
  GnssProfile gnss;
  ReceiverMode gnss_mode = ReceiverMode::kStandalone;
  std::vector<OutputSpec> gnss_outputs;
  std::string gnss_capture;  // every byte sent to PATH and every byte received to PATH.in
  SceneSpec gnss_scene;
  std::optional<double> gnss_ideal_sigma_m;  // the paper's low-fidelity receiver: truth + noise

  GnssEvents gnss_events;  // `events:`, the scheduled impairments
  std::vector<ImuFault> imu_faults;  // `events:` of type imu
  std::vector<TruthFault> truth_faults;  // `events:` of type truth
  std::optional<ControlSpec> control;  // `control:`; none: no live control

  bool imu_enabled = true;
  std::string imu_profile = "paper_phidget";
  std::string imu_log;  // CSV of the samples during `run`; empty: none
  CanSettings imu_can;
  std::vector<CanOutputSpec> imu_outputs;

  bool sched_fifo = false;   // SCHED_FIFO for the loop (needs CAP_SYS_NICE; falls back)
  bool lock_memory = false;  // mlockall (falls back with a message)
  std::optional<int> cpu;    // pin the loop to this CPU (sched_setaffinity); unset: any
};

// One entry of `events:` (configs/default.yaml) into its list of `gnss`, `imu` or `truth`;
// InputError naming the entry's key for bad ones. Also the form of live control's event
// commands.
class YamlMap;
void add_event(YamlMap& m, GnssEvents& gnss, std::vector<ImuFault>& imu, std::vector<TruthFault>& truth);

// The file's configuration; relative paths inside it are relative to the file's folder.
RunConfig load_run_config(const std::filesystem::path& file);
std::filesystem::path default_run_config();  // configs/default.yaml

}  // namespace navemu
