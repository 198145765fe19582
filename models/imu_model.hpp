#pragma once
// MEMS accelerometer and gyroscope error models, in two parameterisations:
//  - the paper's (Durst & Goodin section 2.2): thermal noise from the spring-mass design,
//    quantization from the Allan-variance method, first-order Gauss-Markov bias with
//    correlation time and zero offset, null offsets per axis;
//  - the datasheet's (IEEE Std 952 / 1293 style): white-noise density, bias instability,
//    rate/acceleration random walk, turn-on bias, scale factor and nonlinearity,
//    misalignment, g-sensitivity, temperature coefficients, saturation, resolution,
//    output low-pass filter, decimation and latency.
// Both map onto one plain parameter struct per sensor triad (ImuSensorParams).

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "models/event_window.hpp"
#include "models/geodesy.hpp"
#include "models/imu_kinematics.hpp"
#include "models/random.hpp"
#include "core/time.hpp"

namespace navemu {

// One sensor triad (3 accelerometers or 3 gyroscopes). Units: "unit" = m/s^2 for the
// accelerometer, rad/s for the gyroscope.
struct ImuSensorParams {
  double white_density = 0.0;            // unit/sqrt(Hz) (VRW / ARW), as seen at the output:
                                         // the Allan deviation at tau = 1 s
  double bias_instability = 0.0;         // unit, IEEE Std 952 bias-instability coefficient B:
                                         // realised as a Gauss-Markov bias of 1-sigma
                                         // kGmSigmaPerBiasInstability * B (see below)
  double bias_instability_tau_s = 100.0; // its correlation time
  double random_walk = 0.0;              // unit*sqrt(Hz) (rate random walk / acc. random walk)
  double turn_on_bias_sigma = 0.0;       // unit, drawn once per run
  Vec3 null_offset = Vec3::Zero();       // unit, fixed per axis (the paper's zero offsets)
  double scale_factor_sigma_ppm = 0.0;   // drawn once per run, per axis
  double nonlinearity_ppm = 0.0;         // of full scale, quadratic
  double misalignment_sigma_rad = 0.0;   // cross-axis terms drawn once per run
  double g_sensitivity = 0.0;            // gyroscope only: rad/s per m/s^2
  double bias_temp_coeff_per_c = 0.0;    // unit per degC from the reference temperature
  double scale_temp_coeff_ppm_per_c = 0.0;
  double full_scale = 0.0;               // saturation, unit; 0: none
  double resolution = 0.0;               // LSB, unit; 0: none
  // Per-axis multipliers of the three noise terms (the triad's parts differ per axis): axis i
  // has white density white_density * white_axis_scale[i], Gauss-Markov 1-sigma
  // kGmSigmaPerBiasInstability * bias_instability * bias_axis_scale[i] and random walk
  // random_walk * random_walk_axis_scale[i]. All ones: the triad's values on every axis.
  Vec3 white_axis_scale = Vec3::Ones();
  Vec3 bias_axis_scale = Vec3::Ones();
  Vec3 random_walk_axis_scale = Vec3::Ones();
};

// A first-order Gauss-Markov process of stationary 1-sigma s and correlation time T has the
// Allan variance (IEEE Std 952-1997 annex C; El-Sheimy, Hou & Niu 2008, IEEE Trans. Instrum.
// Meas. 57(1))
//   sigma_A^2(tau) = (2 s^2 T / tau) [1 - (T / (2 tau)) (3 - 4 e^(-tau/T) + e^(-2 tau/T))],
// whose maximum is 0.61736 s (= 0.4365 sqrt(q T), q = 2 s^2 / T) at tau = 1.8926 T. Bias
// instability B shows in the Allan deviation as the flicker floor sqrt(2 ln 2 / pi) B =
// 0.66428 B (IEEE Std 952-1997 C.1.3). Mapping B to s = 0.66428 / 0.61736 B = 1.07600 B makes
// the Gauss-Markov bump peak at exactly that floor value, 0.664 B, around tau = 1.89 T.
inline constexpr double kAllanFlickerFloorPerBiasInstability = 0.66428247;
inline constexpr double kGmAllanPeakPerSigma = 0.61736428;
inline constexpr double kGmAllanPeakTauPerCorrelationTime = 1.8926;
inline constexpr double kGmSigmaPerBiasInstability =
    kAllanFlickerFloorPerBiasInstability / kGmAllanPeakPerSigma;

struct ImuParams {
  std::string name;
  ImuSensorParams accel;
  ImuSensorParams gyro;
  double internal_rate_hz = 1000.0;  // rate of the sensor's own sampling
  double output_rate_hz = 125.0;     // after the low-pass filter and decimation
  double bandwidth_hz = 0.0;         // output low-pass filter (first order); 0: none
  double latency_s = 0.0;            // sample latency
  double reference_temperature_c = 25.0;
};

// The paper's parameterisation (section 2.2) and its mapping onto ImuParams.
struct PaperImuParams {
  // Accelerometer thermal noise sqrt(4 kB T w0 / (m Q)) (m/s^2/sqrt(Hz)).
  double temperature_k = 300.0;
  double accel_omega0_radps = 2.0 * 3.14159265358979 * 2000.0;
  double accel_proof_mass_kg = 1e-9;
  // Gyroscope thermal noise (Q / k) sqrt(4 kB T R B) (rad/s ... see the mapping notes).
  double gyro_k = 1.0;
  double gyro_r_ohm = 1e6;
  double gyro_bandwidth_hz = 50.0;
  double quality_factor = 0.2;  // Q
  // The paper's quantization term 0.01745 sqrt(3 Q^2 / t), t the run time in hours.
  double run_time_h = 1.0;
  // First-order Gauss-Markov bias: correlation time and the "mean offset from zero".
  double tau_s = 10.0;
  double accel_white_noise = 0.12;  // the paper's "white noise process" coefficients: per-sample
  double gyro_white_noise = 0.15;   // 1-sigma at the output rate, m/s^2 and deg/s (section 3)
  Vec3 accel_null_offset = Vec3::Zero();  // m/s^2
  Vec3 gyro_null_offset = Vec3::Zero();   // rad/s
  // 1-sigma of the Gauss-Markov bias about the null offset (m/s^2, rad/s).
  double accel_gm_sigma = 0.0;
  double gyro_gm_sigma = 0.0;
};
ImuParams imu_params_from_paper(const PaperImuParams& p, double output_rate_hz);

// The per-sample 1-sigma of the white noise at the internal rate that gives `white_density` at
// the output after the first-order low-pass filter and decimation of `p` (equal to
// white_density * sqrt(internal_rate_hz) without filter and decimation).
double internal_white_sigma(const ImuParams& p, double white_density);
// Internal samples per output sample.
int imu_decimation(const ImuParams& p);

struct ImuSample {
  GpsTime t;                 // when the sample is output: its time of validity + latency_s
  Vec3 f_body_mps2 = Vec3::Zero();
  Vec3 w_body_radps = Vec3::Zero();
  double temperature_c = 25.0;
  bool saturated = false;        // either of the two below
  bool accel_saturated = false;  // an accelerometer axis was clipped at its range
  bool gyro_saturated = false;   // a rate axis was clipped at its range
};

// Faults of the sensors (issue "impairments", deliverable 3), scheduled like the GNSS events:
// each acts over its window, scaled by the window's level (models/event_window.hpp).
enum class ImuSensor : std::uint8_t { kAccel, kGyro };
enum class ImuFaultKind : std::uint8_t {
  kBias,         // a bias step of `value` (m/s^2, rad/s) x level, ahead of the output filter
  kScale,        // a scale-factor error of `value` ppm x level, ahead of the output filter
  kNoise,        // added white noise of density `value` (unit/sqrt(Hz), as white_density) x level
  kStuck,        // the output holds the last value before the fault while the level is > 0
  kSaturation,   // the output clips at +-`value` (unit) while the level is > 0: a range lost
  kVibration,    // vibration x level: a sinusoid and/or band-limited noise (ImuVibration)
  kTemperature,  // the sensor's temperature `value` degC x level off what it was (both triads):
                 // a ramp drives the datasheet's temperature coefficients
  kDrop,         // output samples lost, each with probability `value` x level (the IMU channel's)
  kDuplicate,    // output samples sent twice, each with probability `value` x level (the channel's)
  kBusOff,       // the CAN controller bus-off while the level is > 0: no frames (the channel's)
  kErrorFrames,  // CAN bus errors, `value` x level error frames per second (the channel's)
};
// Vibration felt by the sensor: a sinusoid of amplitude `value` (unit) at frequency_hz, plus
// random vibration of one-sided power spectral density psd (unit^2/Hz) over [band_lo_hz,
// band_hi_hz], of rms sqrt(psd (band_hi - band_lo)) as a vibration profile's grms
// (MIL-STD-810H method 514.8 specifies random vibration by such an ASD), band-limited by an
// 8th-order Butterworth band-pass. Both are sampled at the internal rate ahead of the output
// filter, so vibration above the output Nyquist frequency aliases as in a real MEMS part.
struct ImuVibration {
  double frequency_hz = 0.0;  // the sinusoid's; 0: none
  double psd = 0.0;           // unit^2/Hz; 0: none
  double band_lo_hz = 0.0, band_hi_hz = 0.0;
};
struct ImuFault {
  EventWindow window;  // from the fault origin (ImuModel::set_faults)
  ImuFaultKind kind = ImuFaultKind::kBias;
  ImuSensor sensor = ImuSensor::kGyro;
  int axis = -1;       // 0, 1, 2: the body frame's x, y, z; -1: all three
  double value = 0.0;
  ImuVibration vibration{};  // kVibration only
};
// Whether a fault can act on a sensor of parameters p: a random vibration's band lies between 0
// and half the internal rate.
bool fault_fits(const ImuFault& f, const ImuParams& p);
// Whether a fault acts in the IMU channel (on whole samples) rather than in the sensor model.
inline bool channel_fault(ImuFaultKind k) {
  return k == ImuFaultKind::kDrop || k == ImuFaultKind::kDuplicate || k == ImuFaultKind::kBusOff ||
         k == ImuFaultKind::kErrorFrames;
}

// The sensor: advanced at its internal rate, emits at its output rate. One random stream per
// error term and axis.
class ImuModel {
 public:
  ImuModel(const ImuParams& p, std::uint64_t seed);
  ~ImuModel();
  ImuModel(const ImuModel&) = delete;
  ImuModel& operator=(const ImuModel&) = delete;

  // Feeds the ideal output valid at time t (called at the internal rate, increasing times);
  // returns true and fills `out` when an output sample is due.
  bool step(GpsTime t, const IdealImu& ideal, double temperature_c, ImuSample& out);
  // The faults from now on, their windows counted from `origin` (channel_fault ones are ignored
  // here). Added noise and random vibration have their own random streams per sensor and axis
  // ("imu.<sensor>.fault_noise", "imu.<sensor>.vibration"), so a run without faults draws
  // exactly what it drew before.
  void set_faults(std::vector<ImuFault> faults, GpsTime origin);
  const ImuParams& params() const { return p_; }

 private:
  struct State;
  void apply_faults(GpsTime t);
  ImuParams p_;
  std::unique_ptr<State> state_;
  std::vector<ImuFault> faults_;
  // Per fault, per axis: the random vibration's band-pass (ImuModel::apply_faults).
  struct Vibration;
  std::vector<Vibration> vibration_;
  GpsTime fault_origin_;
  double fault_sigma_per_density_ = 0.0;
  double temperature_offset_c_ = 0.0;  // kTemperature faults now
};

}  // namespace navemu
