#include "models/imu_model.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace navemu {

namespace {

constexpr double kBoltzmann = 1.380649e-23;  // J/K (SI 2019, exact)
constexpr double kPi = 3.14159265358979323846;
constexpr double kRadPerDeg = kPi / 180.0;
constexpr double kTwoPi = 2.0 * kPi;

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("ImuParams: " + what);
}

void check_sensor(const ImuSensorParams& s, const std::string& name) {
  auto finite_nonneg = [&](double v, const char* field) {
    require(std::isfinite(v) && v >= 0.0, name + "." + field + " must be finite and >= 0");
  };
  finite_nonneg(s.white_density, "white_density");
  finite_nonneg(s.bias_instability, "bias_instability");
  finite_nonneg(s.random_walk, "random_walk");
  finite_nonneg(s.turn_on_bias_sigma, "turn_on_bias_sigma");
  finite_nonneg(s.scale_factor_sigma_ppm, "scale_factor_sigma_ppm");
  finite_nonneg(s.misalignment_sigma_rad, "misalignment_sigma_rad");
  finite_nonneg(s.full_scale, "full_scale");
  finite_nonneg(s.resolution, "resolution");
  require(std::isfinite(s.nonlinearity_ppm), name + ".nonlinearity_ppm must be finite");
  require(std::isfinite(s.g_sensitivity), name + ".g_sensitivity must be finite");
  require(std::isfinite(s.bias_temp_coeff_per_c), name + ".bias_temp_coeff_per_c must be finite");
  require(std::isfinite(s.scale_temp_coeff_ppm_per_c),
          name + ".scale_temp_coeff_ppm_per_c must be finite");
  require(s.null_offset.allFinite(), name + ".null_offset must be finite");
  require(std::isfinite(s.bias_instability_tau_s) && s.bias_instability_tau_s > 0.0,
          name + ".bias_instability_tau_s must be > 0");
  auto positive_vec = [&](const Vec3& v, const char* field) {
    require(v.allFinite() && v.minCoeff() > 0.0, name + "." + field + " must be finite and > 0");
  };
  positive_vec(s.white_axis_scale, "white_axis_scale");
  positive_vec(s.bias_axis_scale, "bias_axis_scale");
  positive_vec(s.random_walk_axis_scale, "random_walk_axis_scale");
}

void check_params(const ImuParams& p) {
  require(std::isfinite(p.internal_rate_hz) && p.internal_rate_hz > 0.0,
          "internal_rate_hz must be > 0");
  require(std::isfinite(p.output_rate_hz) && p.output_rate_hz > 0.0 &&
              p.output_rate_hz <= p.internal_rate_hz * (1.0 + 1e-9),
          "output_rate_hz must be > 0 and <= internal_rate_hz");
  require(std::isfinite(p.bandwidth_hz) && p.bandwidth_hz >= 0.0, "bandwidth_hz must be >= 0");
  require(std::isfinite(p.latency_s) && p.latency_s >= 0.0, "latency_s must be >= 0");
  require(std::isfinite(p.reference_temperature_c), "reference_temperature_c must be finite");
  check_sensor(p.accel, "accel");
  check_sensor(p.gyro, "gyro");
}

// Smoothing factor of the first-order low-pass y_k = y_(k-1) + alpha (x_k - y_(k-1)) at
// bandwidth fc sampled at fs: the pole exp(-2 pi fc / fs) of the impulse-invariant
// discretisation of 1 / (1 + s / (2 pi fc)); DC gain exactly 1. alpha = 1: no filter.
double lowpass_alpha(const ImuParams& p) {
  if (p.bandwidth_hz <= 0.0) return 1.0;
  return 1.0 - std::exp(-2.0 * kPi * p.bandwidth_hz / p.internal_rate_hz);
}

// Standard normal samples by the ziggurat method (Marsaglia & Tsang 2000, J. Stat. Softw. 5(8),
// in the double-precision form of Doornik 2005, "An improved ziggurat method to generate normal
// random samples", ZIGNOR, 128 layers), drawn from RandomStream::uniform() so the result depends
// only on the stream's specified output. About 99 % of the samples need no more than a table
// look-up, against a logarithm per pair for RandomStream::normal().
// pair() makes two samples from the 53 bits of one uniform: 26 bits each, 7 selecting the layer
// and 19 the abscissa inside it (a grid of 2^-18 of the layer's width, finer than 1.4e-5 sigma,
// far below any sensor's resolution); a sample outside its layer's rectangle continues the
// standard rejection loop with fresh full-width uniforms, so the distribution stays exact.
class Ziggurat {
 public:
  Ziggurat() {
    double f = std::exp(-0.5 * kR * kR);
    x_[0] = kV / f;
    x_[1] = kR;
    x_[kLayers] = 0.0;
    for (int i = 2; i < kLayers; ++i) {
      x_[i] = std::sqrt(-2.0 * std::log(kV / x_[i - 1] + f));
      f = std::exp(-0.5 * x_[i] * x_[i]);
    }
    for (int i = 0; i < kLayers; ++i) ratio_[i] = x_[i + 1] / x_[i];
  }

  double operator()(RandomStream& rng) const {
    const std::int64_t bits = draw53(rng);
    return finish(static_cast<int>(bits & 0x7F),
                  2.0 * static_cast<double>(bits >> 7) * 0x1.0p-46 - 1.0, rng);
  }

  void pair(RandomStream& rng, double& a, double& b) const {
    const std::int64_t bits = draw53(rng);
    a = finish(static_cast<int>(bits & 0x7F),
               2.0 * static_cast<double>((bits >> 7) & 0x7FFFF) * 0x1.0p-19 - 1.0, rng);
    b = finish(static_cast<int>((bits >> 26) & 0x7F),
               2.0 * static_cast<double>((bits >> 33) & 0x7FFFF) * 0x1.0p-19 - 1.0, rng);
  }

 private:
  static constexpr int kLayers = 128;
  static constexpr double kR = 3.442619855899;      // start of the tail
  static constexpr double kV = 9.91256303526217e-3;  // area of each layer

  static std::int64_t draw53(RandomStream& rng) {
    return static_cast<std::int64_t>(rng.uniform() * 0x1.0p53);
  }

  // The ziggurat's acceptance test for layer i and abscissa u in [-1, 1); on rejection it
  // starts over with a fresh full-width draw.
  double finish(int i, double u, RandomStream& rng) const {
    for (;;) {
      if (std::abs(u) < ratio_[i]) return u * x_[i];  // inside the layer's rectangle
      if (i == 0) return tail(rng, u < 0.0);
      const double x = u * x_[i];
      const double f0 = std::exp(-0.5 * (x_[i] * x_[i] - x * x));
      const double f1 = std::exp(-0.5 * (x_[i + 1] * x_[i + 1] - x * x));
      if (f1 + (f0 - f1) * rng.uniform() < 1.0) return x;
      const std::int64_t bits = draw53(rng);
      i = static_cast<int>(bits & 0x7F);
      u = 2.0 * static_cast<double>(bits >> 7) * 0x1.0p-46 - 1.0;
    }
  }

  // Beyond kR: Marsaglia's tail method (Doornik 2005, DRanNormalTail).
  static double tail(RandomStream& rng, bool negative) {
    double x, y;
    do {
      x = std::log(1.0 - rng.uniform()) / kR;
      y = std::log(1.0 - rng.uniform());
    } while (-2.0 * y < x * x);
    return negative ? x - kR : kR - x;
  }

  double x_[kLayers + 1];
  double ratio_[kLayers];
};

const Ziggurat kNormal;

}  // namespace

int imu_decimation(const ImuParams& p) {
  const double k = std::round(p.internal_rate_hz / p.output_rate_hz);
  return k < 1.0 ? 1 : static_cast<int>(k);
}

// White noise of per-sample variance v at the internal rate fs, through the first-order filter
// (pole a) and kept every k-th sample: the filtered sequence has variance v (1-a)/(1+a) and
// autocorrelation a^|m|, so the mean of n >> 1 output samples has variance
//   v (1-a)/(1+a) (1+a^k)/(1-a^k) / n,
// against v / (n k) for the mean of all n k internal samples (what a density N = sqrt(v/fs)
// means: sigma_A^2(tau) = N^2 / tau, IEEE Std 952-1997 C.1.1). The ratio
//   r = k (1-a)(1+a^k) / ((1+a)(1-a^k))
// is the aliasing of noise above the output Nyquist frequency (r = k without filter, r -> 1 for
// a filter much narrower than the output rate). Dividing the internal variance by r makes the
// output's Allan deviation at tau = 1 s equal the configured density, as a datasheet density
// (measured at the output) means.
double internal_white_sigma(const ImuParams& p, double white_density) {
  const double k = static_cast<double>(imu_decimation(p));
  const double a = 1.0 - lowpass_alpha(p);
  const double ak = std::pow(a, k);
  const double r = k * (1.0 - a) * (1.0 + ak) / ((1.0 + a) * (1.0 - ak));
  return white_density * std::sqrt(p.internal_rate_hz / r);
}

// The paper's parameterisation (Durst & Goodin, section 2.2 and 3) on the datasheet one.
//  - Thermal noise. Accelerometer sqrt(4 kB T w0 / (m Q)) has the units of a density
//    (m/s^2/sqrt(Hz)) and is used as one. The gyroscope's (Q/k) sqrt(4 kB T R B) is the rms over
//    the noise bandwidth B (Johnson noise sqrt(4 kB T R B)), so its density is that / sqrt(B)
//    (taken as rad/s/sqrt(Hz)).
//  - Quantization: the paper draws, every time step, a normal sample of 1-sigma
//    0.01745 sqrt(3 Q^2 / t) (t the run time in hours; 0.01745 = rad per degree). Per output
//    sample, this is white noise of density sigma / sqrt(output rate); its value is used in
//    rad/s for the gyroscope and, the paper giving no other unit, in m/s^2 for the
//    accelerometer.
//  - "White noise process" coefficients 0.12 (accelerometer, m/s^2) and 0.15 (gyroscope, deg/s,
//    the unit section 3 states for the gyroscope's coefficient): per-sample 1-sigma at the output
//    rate, so density = coefficient / sqrt(output rate).
//  The three white terms are independent and add in variance.
//  - The first-order Gauss-Markov bias sigma(t) = sigma(t-1)/tau + sigma0 with "mean offset
//    from zero" sigma0: realised as the constant null offset per axis (sigma0, which the paper
//    takes from field data) plus the exact discrete Gauss-Markov recursion
//    b_k = exp(-dt/tau) b_(k-1) + w_k, Var(w_k) = s^2 (1 - exp(-2 dt/tau)) (Brown & Hwang 2.9)
//    of correlation time tau and 1-sigma s = accel_gm_sigma / gyro_gm_sigma. Expressed as
//    bias_instability = s / kGmSigmaPerBiasInstability so the model's mapping gives back s.
//  The paper's Gauss-Markov scale-factor error is not modelled separately (no turn-on scale or
//  scale Gauss-Markov: all other datasheet terms are zero).
ImuParams imu_params_from_paper(const PaperImuParams& p, double output_rate_hz) {
  require(std::isfinite(output_rate_hz) && output_rate_hz > 0.0, "output_rate_hz must be > 0");
  require(p.quality_factor > 0.0 && p.run_time_h > 0.0 && p.tau_s > 0.0 &&
              p.accel_proof_mass_kg > 0.0 && p.gyro_k > 0.0 && p.gyro_bandwidth_hz > 0.0,
          "paper parameters Q, run time, tau, proof mass, k and B must be > 0");
  const double four_kt = 4.0 * kBoltzmann * p.temperature_k;
  const double accel_thermal =
      std::sqrt(four_kt * p.accel_omega0_radps / (p.accel_proof_mass_kg * p.quality_factor));
  const double gyro_thermal = (p.quality_factor / p.gyro_k) *
                              std::sqrt(four_kt * p.gyro_r_ohm * p.gyro_bandwidth_hz) /
                              std::sqrt(p.gyro_bandwidth_hz);
  const double quant_sigma =
      0.01745 * std::sqrt(3.0 * p.quality_factor * p.quality_factor / p.run_time_h);
  const double rt = std::sqrt(output_rate_hz);
  const double accel_white = p.accel_white_noise / rt;
  const double gyro_white = p.gyro_white_noise * kRadPerDeg / rt;
  const double quant_density = quant_sigma / rt;

  ImuParams out;
  out.name = "paper";
  out.output_rate_hz = output_rate_hz;
  out.internal_rate_hz = output_rate_hz;  // the paper samples once per time step
  out.accel.white_density = std::sqrt(accel_white * accel_white + accel_thermal * accel_thermal +
                                      quant_density * quant_density);
  out.gyro.white_density = std::sqrt(gyro_white * gyro_white + gyro_thermal * gyro_thermal +
                                     quant_density * quant_density);
  out.accel.bias_instability = p.accel_gm_sigma / kGmSigmaPerBiasInstability;
  out.gyro.bias_instability = p.gyro_gm_sigma / kGmSigmaPerBiasInstability;
  out.accel.bias_instability_tau_s = p.tau_s;
  out.gyro.bias_instability_tau_s = p.tau_s;
  out.accel.null_offset = p.accel_null_offset;
  out.gyro.null_offset = p.gyro_null_offset;
  out.reference_temperature_c = p.temperature_k - 273.15;
  return out;
}

// Per-triad state. Every random term has its own stream per axis (../shared/DESIGN.md),
// named "imu.<accel|gyro>.<term>" with the axis as index.
struct ImuModel::State {
  struct Triad {
    Triad(const ImuSensorParams& sp, const ImuParams& p, std::uint64_t seed, const char* sensor)
        : white{stream(seed, sensor, "white", 0), stream(seed, sensor, "white", 1),
                stream(seed, sensor, "white", 2)},
          gm{stream(seed, sensor, "gm", 0), stream(seed, sensor, "gm", 1),
             stream(seed, sensor, "gm", 2)},
          rw{stream(seed, sensor, "rw", 0), stream(seed, sensor, "rw", 1),
             stream(seed, sensor, "rw", 2)},
          fault_noise{stream(seed, sensor, "fault_noise", 0), stream(seed, sensor, "fault_noise", 1),
                      stream(seed, sensor, "fault_noise", 2)},
          vibration{stream(seed, sensor, "vibration", 0), stream(seed, sensor, "vibration", 1),
                    stream(seed, sensor, "vibration", 2)} {
      const double dt = 1.0 / p.internal_rate_hz;
      // Bias instability: Gauss-Markov of 1-sigma kGmSigmaPerBiasInstability * B (header), exact
      // discretisation as models/random.hpp GaussMarkov, with phi precomputed. The three noise
      // terms per axis, with the per-axis multipliers (exactly the triad's values at 1).
      const double gm_sigma_triad = kGmSigmaPerBiasInstability * sp.bias_instability;
      gm_phi = std::exp(-dt / sp.bias_instability_tau_s);
      Vec3 gm_sigma;
      for (int i = 0; i < 3; ++i) {
        white_sigma[i] = internal_white_sigma(p, sp.white_density * sp.white_axis_scale[i]);
        gm_sigma[i] = gm_sigma_triad * sp.bias_axis_scale[i];
        gm_q[i] = gm_sigma[i] * std::sqrt(1.0 - gm_phi * gm_phi);
        rw_step[i] = sp.random_walk * sp.random_walk_axis_scale[i] * std::sqrt(dt);
      }
      // Quadratic nonlinearity: error k2 x^2 reaching nonlinearity_ppm of full scale at full
      // scale (needs a full scale to refer to).
      k2 = sp.full_scale > 0.0 ? sp.nonlinearity_ppm * 1e-6 / sp.full_scale : 0.0;
      scale_temp = sp.scale_temp_coeff_ppm_per_c * 1e-6;
      bias_temp = sp.bias_temp_coeff_per_c;
      g_sens = sp.g_sensitivity;
      full_scale = sp.full_scale;
      resolution = sp.resolution;
      // Drawn once per run: turn-on bias, scale factor, cross-axis misalignment
      // M = I + [0 m01 m02; m10 0 m12; m20 m21 0].
      M.setIdentity();
      for (int i = 0; i < 3; ++i) {
        RandomStream turn_on = stream(seed, sensor, "turn_on", i);
        RandomStream scale_rng = stream(seed, sensor, "scale", i);
        RandomStream mis = stream(seed, sensor, "misalignment", i);
        bias_const[i] = sp.null_offset[i] + sp.turn_on_bias_sigma * turn_on.normal();
        scale[i] = 1.0 + sp.scale_factor_sigma_ppm * 1e-6 * scale_rng.normal();
        for (int j = 0; j < 3; ++j)
          if (j != i) M(i, j) = sp.misalignment_sigma_rad * mis.normal();
        gm_x[i] = gm_sigma[i] * gm[static_cast<std::size_t>(i)].normal();  // stationary start
      }
      has_misalignment = sp.misalignment_sigma_rad > 0.0;
    }

    static RandomStream stream(std::uint64_t seed, const char* sensor, const char* term,
                               int axis) {
      return RandomStream(seed, stream_id(std::string("imu.") + sensor + "." + term, axis));
    }

    // The sensed value before low-pass filtering, of ideal input x (and specific force f for the
    // g-sensitivity of a gyroscope), temperature offset dT from the reference.
    void sense(const Vec3& ideal, const Vec3& f, double dT, Vec3& y) {
      const Vec3 v = has_misalignment ? Vec3(M * ideal) : ideal;
      // Normals come in pairs per stream (Ziggurat::pair): drawn on even steps, the second
      // one kept for the odd step.
      if (!have_spare) {
        for (std::size_t i = 0; i < 3; ++i) {
          kNormal.pair(white[i], n_white[i][0], n_white[i][1]);
          kNormal.pair(gm[i], n_gm[i][0], n_gm[i][1]);
          kNormal.pair(rw[i], n_rw[i][0], n_rw[i][1]);
        }
      }
      const std::size_t k = have_spare ? 1 : 0;
      have_spare = !have_spare;
      for (int i = 0; i < 3; ++i) {
        const auto ui = static_cast<std::size_t>(i);
        const double x = v[i];
        gm_x[i] = gm_phi * gm_x[i] + gm_q[i] * n_gm[ui][k];
        rw_x[i] += rw_step[i] * n_rw[ui][k];
        y[i] = (scale[i] + scale_temp * dT + k2 * x) * x + bias_const[i] + gm_x[i] + rw_x[i] +
               bias_temp * dT + white_sigma[i] * n_white[ui][k] + g_sens * f[i];
        if (faulty) {
          y[i] += fault_scale[i] * x + fault_bias[i];
          if (fault_sigma[i] > 0.0) y[i] += fault_sigma[i] * kNormal(fault_noise[ui]);
        }
      }
    }

    // Resolution (round to the nearest LSB) then saturation at +-full scale (or a saturation
    // fault's narrower range).
    bool finish(Vec3& y) const {
      bool sat = false;
      for (int i = 0; i < 3; ++i) {
        double x = y[i];
        if (resolution > 0.0) x = resolution * std::nearbyint(x / resolution);
        double range = full_scale;
        if (fault_range[i] > 0.0 && (range <= 0.0 || fault_range[i] < range)) range = fault_range[i];
        if (range > 0.0 && std::abs(x) > range) {
          x = std::copysign(range, x);
          sat = true;
        }
        y[i] = x;
      }
      return sat;
    }

    std::array<RandomStream, 3> white, gm, rw, fault_noise, vibration;
    // The faults' terms at the current step (ImuModel::apply_faults); stuck axes hold `held`;
    // fault_range: a saturation fault's range, 0 none.
    bool faulty = false;
    Vec3 fault_scale = Vec3::Zero(), fault_bias = Vec3::Zero(), fault_sigma = Vec3::Zero();
    Vec3 fault_range = Vec3::Zero();
    std::array<bool, 3> stuck{};
    Vec3 held = Vec3::Zero();  // the last output sample
    double n_white[3][2] = {}, n_gm[3][2] = {}, n_rw[3][2] = {};
    bool have_spare = false;
    Eigen::Matrix3d M;
    bool has_misalignment = false;
    Vec3 scale = Vec3::Ones();
    Vec3 bias_const = Vec3::Zero();
    Vec3 gm_x = Vec3::Zero();
    Vec3 rw_x = Vec3::Zero();
    Vec3 white_sigma = Vec3::Zero(), gm_q = Vec3::Zero(), rw_step = Vec3::Zero();
    double gm_phi = 1.0, k2 = 0.0;
    double scale_temp = 0.0, bias_temp = 0.0, g_sens = 0.0, full_scale = 0.0, resolution = 0.0;
  };

  State(const ImuParams& p, std::uint64_t seed)
      : accel(p.accel, p, seed, "accel"),
        gyro(p.gyro, p, seed, "gyro"),
        alpha(lowpass_alpha(p)),
        decimation(imu_decimation(p)),
        latency_ns(static_cast<std::int64_t>(std::llround(p.latency_s * 1e9))) {
    accel.g_sens = 0.0;  // g-sensitivity is a gyroscope term
  }

  Triad accel, gyro;
  double alpha;
  int decimation;
  std::int64_t latency_ns;
  Vec3 lp_f = Vec3::Zero(), lp_w = Vec3::Zero();
  std::int64_t n = 0;  // internal samples so far
};

// The random vibration's shaping filter: a band-pass of a 4th-order Butterworth high-pass at
// band_lo and a 4th-order Butterworth low-pass at band_hi, each two biquads of R. Bristow-Johnson's
// "Audio EQ Cookbook" (HPF/LPF, bilinear transform warped at the corner) with the Butterworth
// section Qs 1 / (2 cos((2k - 1) pi / 8)), k = 1, 2. It is fed with white noise of 1-sigma
// `sigma` chosen so that the output's variance is exactly psd (hi - lo): Var = sigma^2 sum(h_n^2),
// the sum of the squared impulse response, summed once here. The passband's PSD is then psd less
// the few per cent the skirts take.
struct ImuModel::Vibration {
  struct Biquad {  // normalised (a0 = 1), transposed direct form II
    double b0 = 0.0, b1 = 0.0, b2 = 0.0, a1 = 0.0, a2 = 0.0;
    double step(double x, double& z1, double& z2) const {
      const double y = b0 * x + z1;
      z1 = b1 * x - a1 * y + z2;
      z2 = b2 * x - a2 * y;
      return y;
    }
  };
  static Biquad section(bool high_pass, double f_hz, double q, double fs_hz) {
    const double w0 = kTwoPi * f_hz / fs_hz, c = std::cos(w0), alpha = std::sin(w0) / (2.0 * q);
    const double a0 = 1.0 + alpha, b = high_pass ? (1.0 + c) / 2.0 : (1.0 - c) / 2.0;
    return {b / a0, (high_pass ? -2.0 : 2.0) * b / a0, b / a0, -2.0 * c / a0, (1.0 - alpha) / a0};
  }
  static constexpr std::size_t kSections = 4;
  using Memory = std::array<std::array<double, 2>, kSections>;  // z1, z2 per section

  Vibration() = default;
  Vibration(const ImuVibration& v, double fs_hz) {
    if (v.psd <= 0.0) return;
    const double q[2] = {1.0 / (2.0 * std::cos(kTwoPi / 16.0)), 1.0 / (2.0 * std::cos(3.0 * kTwoPi / 16.0))};
    for (std::size_t k = 0; k < 2; ++k) {
      sections[k] = section(true, v.band_lo_hz, q[k], fs_hz);
      sections[k + 2] = section(false, v.band_hi_hz, q[k], fs_hz);
    }
    Memory z{};
    double energy = 0.0;
    for (int n = 0; n < 100'000'000; ++n) {
      const double h = filter(n == 0 ? 1.0 : 0.0, z);
      energy += h * h;
      double left = 0.0;
      for (const auto& m : z) left += m[0] * m[0] + m[1] * m[1];
      if (n > 1000 && h * h + left < 1e-20 * energy) break;
    }
    sigma = std::sqrt(v.psd * (v.band_hi_hz - v.band_lo_hz) / energy);
  }
  double filter(double x, Memory& z) const {
    for (std::size_t k = 0; k < kSections; ++k) x = sections[k].step(x, z[k][0], z[k][1]);
    return x;
  }
  std::array<Biquad, kSections> sections{};
  double sigma = 0.0;
  std::array<Memory, 3> memory{};  // per axis
};

ImuModel::ImuModel(const ImuParams& p, std::uint64_t seed) : p_(p) {
  check_params(p_);
  state_ = std::make_unique<State>(p_, seed);
}

ImuModel::~ImuModel() = default;

// One internal sample: (1 + s + s_T(T) + k2 x) (M x) + turn-on + null offset + b_GM + b_RW +
// b_T(T) + white + g-sensitivity, through the output low-pass; every k-th sample is quantized,
// saturated and emitted at t + latency.
bool ImuModel::step(GpsTime t, const IdealImu& ideal, double temperature_c, ImuSample& out) {
  State& s = *state_;
  if (!faults_.empty()) apply_faults(t);
  temperature_c += temperature_offset_c_;
  const double dT = temperature_c - p_.reference_temperature_c;
  Vec3 yf, yw;
  s.accel.sense(ideal.f_body_mps2, ideal.f_body_mps2, dT, yf);
  s.gyro.sense(ideal.w_ib_body_radps, ideal.f_body_mps2, dT, yw);
  if (s.n == 0 || s.alpha >= 1.0) {
    s.lp_f = yf;  // the filter starts settled on the first sample
    s.lp_w = yw;
  } else {
    s.lp_f += s.alpha * (yf - s.lp_f);
    s.lp_w += s.alpha * (yw - s.lp_w);
  }
  const bool due = s.n % s.decimation == 0;
  ++s.n;
  if (!due) return false;
  out.f_body_mps2 = s.lp_f;
  out.w_body_radps = s.lp_w;
  const bool sat_f = s.accel.finish(out.f_body_mps2);
  const bool sat_w = s.gyro.finish(out.w_body_radps);
  for (int i = 0; i < 3; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    if (s.accel.stuck[ui]) out.f_body_mps2[i] = s.accel.held[i];
    if (s.gyro.stuck[ui]) out.w_body_radps[i] = s.gyro.held[i];
  }
  s.accel.held = out.f_body_mps2;
  s.gyro.held = out.w_body_radps;
  out.accel_saturated = sat_f;
  out.gyro_saturated = sat_w;
  out.saturated = sat_f || sat_w;
  out.t = GpsTime{t.ns + s.latency_ns};
  out.temperature_c = temperature_c;
  return true;
}

bool fault_fits(const ImuFault& f, const ImuParams& p) {
  return f.kind != ImuFaultKind::kVibration || f.vibration.psd <= 0.0 ||
         (f.vibration.band_lo_hz > 0.0 && f.vibration.band_lo_hz < f.vibration.band_hi_hz &&
          f.vibration.band_hi_hz < p.internal_rate_hz / 2.0);
}

void ImuModel::set_faults(std::vector<ImuFault> faults, GpsTime origin) {
  for (const ImuFault& f : faults)
    require(fault_fits(f, p_), "a random vibration's band must lie between 0 and half the internal rate");
  faults_ = std::move(faults);
  fault_origin_ = origin;
  fault_sigma_per_density_ = internal_white_sigma(p_, 1.0);
  vibration_.clear();
  for (const ImuFault& f : faults_)
    vibration_.push_back(f.kind == ImuFaultKind::kVibration ? Vibration(f.vibration, p_.internal_rate_hz) : Vibration());
  temperature_offset_c_ = 0.0;
  for (State::Triad* tr : {&state_->accel, &state_->gyro}) {
    tr->faulty = false;
    tr->stuck = {};
    tr->fault_range.setZero();
  }
}

// The faults' sum at t: bias steps, scale errors, vibration and temperature offsets add, noise
// densities add in variance (each at the internal rate as internal_white_sigma() sets the
// model's own white noise), an axis is stuck while any stuck fault on it is active and clips at
// the narrowest active saturation range.
void ImuModel::apply_faults(GpsTime t) {
  const double t_s = seconds_between(t, fault_origin_);
  for (State::Triad* tr : {&state_->accel, &state_->gyro}) {
    tr->fault_scale.setZero();
    tr->fault_bias.setZero();
    tr->fault_sigma.setZero();
    tr->fault_range.setZero();
    tr->stuck = {};
  }
  temperature_offset_c_ = 0.0;
  for (std::size_t k = 0; k < faults_.size(); ++k) {
    const ImuFault& f = faults_[k];
    const double level = event_level(f.window, t_s);
    if (level <= 0.0 || channel_fault(f.kind)) continue;
    if (f.kind == ImuFaultKind::kTemperature) {
      temperature_offset_c_ += f.value * level;
      continue;
    }
    State::Triad& tr = f.sensor == ImuSensor::kGyro ? state_->gyro : state_->accel;
    const double sine = f.kind == ImuFaultKind::kVibration && f.vibration.frequency_hz > 0.0
                            ? f.value * std::sin(kTwoPi * f.vibration.frequency_hz * (t_s - f.window.start_s))
                            : 0.0;
    for (int i = 0; i < 3; ++i) {
      if (f.axis >= 0 && f.axis != i) continue;
      const auto ui = static_cast<std::size_t>(i);
      switch (f.kind) {
        case ImuFaultKind::kBias: tr.fault_bias[i] += f.value * level; break;
        case ImuFaultKind::kScale: tr.fault_scale[i] += f.value * 1e-6 * level; break;
        case ImuFaultKind::kNoise: {
          const double sigma = f.value * level * fault_sigma_per_density_;
          tr.fault_sigma[i] = std::hypot(tr.fault_sigma[i], sigma);
          break;
        }
        case ImuFaultKind::kStuck: tr.stuck[ui] = true; break;
        case ImuFaultKind::kSaturation:
          if (tr.fault_range[i] <= 0.0 || f.value < tr.fault_range[i]) tr.fault_range[i] = f.value;
          break;
        case ImuFaultKind::kVibration: {
          Vibration& v = vibration_[k];
          double random = 0.0;
          if (v.sigma > 0.0) random = v.filter(v.sigma * kNormal(tr.vibration[ui]), v.memory[ui]);
          tr.fault_bias[i] += level * (sine + random);
          break;
        }
        default: break;
      }
    }
  }
  for (State::Triad* tr : {&state_->accel, &state_->gyro})
    tr->faulty = !tr->fault_scale.isZero() || !tr->fault_bias.isZero() || !tr->fault_sigma.isZero();
}

}  // namespace navemu
