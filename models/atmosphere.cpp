#include "models/atmosphere.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace navemu {

// IS-GPS-200 20.3.3.5.2.5 and Figure 20-4 ("Ionospheric Model"). Angles in the figure are in
// semicircles; the trigonometric functions take semicircles times pi.
double klobuchar_delay_l1_s(const KlobucharCoefficients& k, const Geodetic& rx, const AzEl& dir,
                            GpsTime t) {
  // No line of sight below the horizon (as RTKLIB's ionmodel: zero delay).
  if (dir.el_rad <= 0.0) return 0.0;

  const double phi_u = rx.lat_deg / 180.0;  // user geodetic latitude, semicircles
  const double lambda_u = rx.lon_deg / 180.0;  // user geodetic longitude, semicircles
  const double e = dir.el_rad / kPi;           // elevation angle E, semicircles
  const double a = dir.az_rad;                 // azimuth A (cos/sin taken in radians)

  // Earth-centred angle between user and ionospheric pierce point, semicircles.
  const double psi = 0.0137 / (e + 0.11) - 0.022;

  // Geodetic latitude of the pierce point, limited to +-0.416 semicircles.
  const double phi_i = std::clamp(phi_u + psi * std::cos(a), -0.416, 0.416);

  // Geodetic longitude of the pierce point, semicircles.
  const double lambda_i = lambda_u + psi * std::sin(a) / std::cos(phi_i * kPi);

  // Geomagnetic latitude of the pierce point, semicircles.
  const double phi_m = phi_i + 0.064 * std::cos((lambda_i - 1.617) * kPi);

  // Local time at the pierce point, s, in [0, 86400).
  double t_local = std::fmod(4.32e4 * lambda_i + to_week_tow(t).tow_s, 86400.0);
  if (t_local < 0.0) t_local += 86400.0;

  // Amplitude (s) and period (s) of the cosine model, cubic in phi_m, with their floors.
  double amp = 0.0;
  double per = 0.0;
  double phi_m_n = 1.0;
  for (std::size_t n = 0; n < 4; ++n) {
    amp += k.alpha[n] * phi_m_n;
    per += k.beta[n] * phi_m_n;
    phi_m_n *= phi_m;
  }
  amp = std::max(amp, 0.0);
  per = std::max(per, 72000.0);

  // Phase, radians.
  const double x = 2.0 * kPi * (t_local - 50400.0) / per;

  // Obliquity factor.
  const double f = 1.0 + 16.0 * std::pow(0.53 - e, 3);

  if (std::abs(x) < 1.57) {
    const double x2 = x * x;
    return f * (5.0e-9 + amp * (1.0 - x2 / 2.0 + x2 * x2 / 24.0));
  }
  return f * 5.0e-9;  // night-time constant delay
}

// RTKLIB tropmodel's standard atmosphere: p = 1013.25 (1 - 2.2557e-5 h)^5.2568 hPa,
// T = 15 - 6.5e-3 h degC (converted with +273.16 as RTKLIB does); heights below 0 taken as 0.
Meteo standard_atmosphere(double h_m, double relative_humidity) {
  const double h = std::max(h_m, 0.0);
  // The pressure law has no meaning above ~44 km where its base turns negative.
  const double base = std::max(1.0 - 2.2557e-5 * h, 0.0);
  Meteo m;
  m.pressure_hpa = 1013.25 * std::pow(base, 5.2568);
  m.temperature_k = 15.0 - 6.5e-3 * h + 273.16;
  m.relative_humidity = relative_humidity;
  return m;
}

// Saastamoinen (1972) with the 1/cos(z) mapping, in the form of RTKLIB's tropmodel:
//   e     = 6.108 RH exp((17.15 T - 4684) / (T - 38.45))          water vapour pressure, hPa
//   z     = pi/2 - el                                              zenith angle
//   hydro = 0.0022768 P / (1 - 0.00266 cos 2phi - 0.00028 h_km) / cos z   (Davis et al. 1985)
//   wet   = 0.002277 (1255 / T + 0.05) e / cos z
// RTKLIB's domain is kept so that corrections match rnx2rtkp: zero delay at or below the
// horizon and for heights outside [-100 m, 10 km]; heights below 0 are taken as 0.
TropoDelay saastamoinen_delay(const Geodetic& rx, double el_rad, const Meteo& m) {
  TropoDelay d;
  if (rx.h_m < -100.0 || rx.h_m > 1.0e4 || el_rad <= 0.0) return d;
  const double h = std::max(rx.h_m, 0.0);
  const double t = m.temperature_k;
  const double e = 6.108 * m.relative_humidity * std::exp((17.15 * t - 4684.0) / (t - 38.45));
  const double z = kPi / 2.0 - el_rad;
  const double cos_z = std::cos(z);
  const double lat_rad = rx.lat_deg * kDegToRad;
  d.hydrostatic_m = 0.0022768 * m.pressure_hpa /
                    (1.0 - 0.00266 * std::cos(2.0 * lat_rad) - 0.00028 * h / 1.0e3) / cos_z;
  d.wet_m = 0.002277 * (1255.0 / t + 0.05) * e / cos_z;
  return d;
}

}  // namespace navemu
