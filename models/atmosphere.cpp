#include "models/atmosphere.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace navemu {

// IS-GPS-200 20.3.3.5.2.5 and Figure 20-4 ("Ionospheric Model"). Angles in the figure are in
// semicircles; the trigonometric functions take semicircles times pi.
double klobuchar_delay_l1_s(const KlobucharCoefficients& k, const Geodetic& rx, const AzEl& dir,
                            GpsTime t) {
  return klobuchar_delay_l1_s(k, rx, dir, to_week_tow(t).tow_s);
}

double klobuchar_delay_l1_s(const KlobucharCoefficients& k, const Geodetic& rx, const AzEl& dir,
                            double gps_tow_s) {
  return klobuchar_delay_l1_s(k, rx, direction(dir), gps_tow_s);
}

double klobuchar_delay_l1_s(const KlobucharCoefficients& k, const Geodetic& rx, const Direction& dir,
                            double gps_tow_s) {
  // No line of sight below the horizon (as RTKLIB's ionmodel: zero delay).
  if (dir.az_el.el_rad <= 0.0) return 0.0;

  const double phi_u = rx.lat_deg / 180.0;  // user geodetic latitude, semicircles
  const double lambda_u = rx.lon_deg / 180.0;  // user geodetic longitude, semicircles
  const double e = dir.az_el.el_rad / kPi;     // elevation angle E, semicircles

  // Earth-centred angle between user and ionospheric pierce point, semicircles.
  const double psi = 0.0137 / (e + 0.11) - 0.022;

  // Geodetic latitude of the pierce point, limited to +-0.416 semicircles.
  const double phi_i = std::clamp(phi_u + psi * dir.cos_az, -0.416, 0.416);

  // Geodetic longitude of the pierce point, semicircles.
  const double lambda_i = lambda_u + psi * dir.sin_az / std::cos(phi_i * kPi);

  // Geomagnetic latitude of the pierce point, semicircles.
  const double phi_m = phi_i + 0.064 * std::cos((lambda_i - 1.617) * kPi);

  // Local time at the pierce point, s, in [0, 86400).
  double t_local = std::fmod(4.32e4 * lambda_i + gps_tow_s, 86400.0);
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

  // Obliquity factor (the cube by multiplication: within an ulp or two of pow's).
  const double d = 0.53 - e;
  const double f = 1.0 + 16.0 * (d * d * d);

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
  return saastamoinen_delay(saastamoinen_zenith(rx, m), el_rad);
}

SaastamoinenZenith saastamoinen_zenith(const Geodetic& rx, const Meteo& m) {
  SaastamoinenZenith z;
  z.in_domain = !(rx.h_m < kSaastamoinenLowest_m || rx.h_m > 1.0e4);
  if (!z.in_domain) return z;
  const double h = std::max(rx.h_m, 0.0);
  const double t = m.temperature_k;
  const double e = 6.108 * m.relative_humidity * std::exp((17.15 * t - 4684.0) / (t - 38.45));
  const double lat_rad = rx.lat_deg * kDegToRad;
  z.hydrostatic_m =
      0.0022768 * m.pressure_hpa / (1.0 - 0.00266 * std::cos(2.0 * lat_rad) - 0.00028 * h / 1.0e3);
  z.wet_m = 0.002277 * (1255.0 / t + 0.05) * e;
  return z;
}

TropoDelay saastamoinen_delay(const SaastamoinenZenith& zenith, double el_rad) {
  TropoDelay d;
  if (!zenith.in_domain || el_rad <= 0.0) return d;
  const double z = kPi / 2.0 - el_rad;
  const double cos_z = std::cos(z);
  d.hydrostatic_m = zenith.hydrostatic_m / cos_z;
  d.wet_m = zenith.wet_m / cos_z;
  return d;
}

// ---- Ionosphere, first-order -----------------------------------------------------------------

namespace {

// 1 TECU = 1e16 electrons/m^2.
constexpr double kElectronsPerTecu = 1.0e16;
// First-order ionospheric group delay constant 40.3 m^3/s^2: the first-order term of the
// Appleton-Hartree refractive index, e^2 / (8 pi^2 eps0 m_e) = 40.31 (SI units).
constexpr double kIonoK_m3ps2 = 40.3;

}  // namespace

double iono_zenith_delay_m(double vtec_tecu, double freq_hz) {
  return kIonoK_m3ps2 * vtec_tecu * kElectronsPerTecu / (freq_hz * freq_hz);
}

// Durst & Goodin, section 2.1 (after Montenbruck): 2.037 / (sqrt(sin^2 el + 0.076) + sin el).
// Rewritten as 2.037 (sqrt(sin^2 el + 0.076) - sin el) / 0.076, it is the slant-to-vertical
// path ratio through a spherical layer of thickness H with 2H/R + (H/R)^2 = 0.076 (H ~ 240 km);
// it is 0.99985 at the zenith and 2.037/sqrt(0.076) = 7.389 at the horizon. Negative
// elevations are taken as the horizon.
double iono_paper_mapping(double el_rad) {
  const double s = std::sin(std::clamp(el_rad, 0.0, kPi / 2.0));
  return 2.037 / (std::sqrt(s * s + 0.076) + s);
}

// The first-order delay scales with 1/f^2 (IS-GPS-200 20.3.3.3.3.2 writes the L1/L2 ratio as
// gamma = (f_L1 / f_L2)^2 = (77/60)^2).
double iono_scale_from_l1(double delay_l1, double freq_hz) {
  const double ratio = kGpsL1_Hz / freq_hz;
  return delay_l1 * ratio * ratio;
}

// ---- Troposphere with meteorology and Niell mapping -------------------------------------------

// Magnus-type saturation pressure over water in the form RTKLIB's tropmodel uses,
//   e_s = 6.108 exp((17.15 T - 4684) / (T - 38.45)) hPa, T in K,
// i.e. 6.108 exp((17.15 t + 0.47) / (t + 234.7)) with t in degC (T = t + 273.15). It lies
// 0.2 % (0 degC) to 0.8 % (35 degC) above the Magnus-Tetens 6.1078 exp(17.27 t / (t + 237.3)).
// Using the same law as saastamoinen_delay keeps a Meteo's humidity meaning the same in both
// models.
double saturation_vapour_pressure_hpa(double temperature_k) {
  const double t = temperature_k;
  return 6.108 * std::exp((17.15 * t - 4684.0) / (t - 38.45));
}

double water_vapour_pressure_hpa(const Meteo& m) {
  return m.relative_humidity * saturation_vapour_pressure_hpa(m.temperature_k);
}

// Hydrostatic: Saastamoinen (1972) as refined by Davis et al. (1985), Radio Science 20(6),
// 1593-1607 (the form of the IERS Conventions (2010), chapter 9):
//   ZHD = 0.0022768 P / (1 - 0.00266 cos 2phi - 0.00028 H_km)   [m, P in hPa]
// The paper's "2.2779 P / (1 - 0.00266 cos 2theta - 0.0028 h)" is the same law written for
// a delay in millimetres with P in hPa (2.2779 mm/hPa = 0.0022779 m/hPa, a published variant
// of the constant 0.05 % above Davis et al.'s 2.2768: ~1 mm at the zenith). Its term "0.0028 h"
// matches 0.00028 H only with h in units of 10 km; 0.00028 per km is what Saastamoinen and
// Davis give, so that is what is used here, with the ellipsoidal height.
// Wet: Saastamoinen (1972), ZWD = 0.002277 (1255 / T + 0.05) e  [m, T in K, e in hPa], with
// e = RH e_s(T) from saturation_vapour_pressure_hpa.
TropoDelay tropo_zenith_delay(const Geodetic& rx, const Meteo& m) {
  const double lat_rad = rx.lat_deg * kDegToRad;
  const double h_km = rx.h_m / 1.0e3;
  TropoDelay d;
  d.hydrostatic_m =
      0.0022768 * m.pressure_hpa / (1.0 - 0.00266 * std::cos(2.0 * lat_rad) - 0.00028 * h_km);
  d.wet_m = 0.002277 * (1255.0 / m.temperature_k + 0.05) * water_vapour_pressure_hpa(m);
  return d;
}

namespace {

// Coefficient tables of Niell (1996), "Global mapping functions for the atmosphere delay at
// radio wavelengths", JGR 101(B2), 3227-3246. Every value was checked against several
// published copies: Leick, GPS Satellite Surveying, Tables 6.1 (hydrostatic) and 6.2 (wet);
// the UNB3m_pack look-up tables (Leandro, Langley & Santos 2008, GPS Solutions 12(1), 65-70);
// the wet table at benthamopen.com/FULLTEXT/TOASCJ-11-1/TABLE/T1; and the NMF tables of
// GpsTools (T. Takasu) and nuSolve (SgMappingFunction).
constexpr std::array<double, 5> kNiellLat_deg{15.0, 30.0, 45.0, 60.0, 75.0};

// Hydrostatic, average.
constexpr std::array<double, 5> kNiellHydAvgA{1.2769934e-3, 1.2683230e-3, 1.2465397e-3,
                                              1.2196049e-3, 1.2045996e-3};
constexpr std::array<double, 5> kNiellHydAvgB{2.9153695e-3, 2.9152299e-3, 2.9288445e-3,
                                              2.9022565e-3, 2.9024912e-3};
constexpr std::array<double, 5> kNiellHydAvgC{62.610505e-3, 62.837393e-3, 63.721774e-3,
                                              63.824265e-3, 64.258455e-3};
// Hydrostatic, amplitude of the annual term.
constexpr std::array<double, 5> kNiellHydAmpA{0.0, 1.2709626e-5, 2.6523662e-5, 3.4000452e-5,
                                              4.1202191e-5};
constexpr std::array<double, 5> kNiellHydAmpB{0.0, 2.1414979e-5, 3.0160779e-5, 7.2562722e-5,
                                              11.723375e-5};
constexpr std::array<double, 5> kNiellHydAmpC{0.0, 9.0128400e-5, 4.3497037e-5, 84.795348e-5,
                                              170.37206e-5};
// Height correction coefficients a_ht, b_ht, c_ht.
constexpr double kNiellHtA = 2.53e-5;
constexpr double kNiellHtB = 5.49e-3;
constexpr double kNiellHtC = 1.14e-3;
// Wet.
constexpr std::array<double, 5> kNiellWetA{5.8021897e-4, 5.6794847e-4, 5.8118019e-4,
                                           5.9727542e-4, 6.1641693e-4};
constexpr std::array<double, 5> kNiellWetB{1.4275268e-3, 1.5138625e-3, 1.4572752e-3,
                                           1.5007428e-3, 1.7599082e-3};
constexpr std::array<double, 5> kNiellWetC{4.3472961e-2, 4.6729510e-2, 4.3908931e-2,
                                           4.4626982e-2, 5.4736038e-2};

// Day of year of the hydrostatic coefficients' minimum in the northern hemisphere (Jan 28).
constexpr double kNiellT0_doy = 28.0;
constexpr double kDaysPerYear = 365.25;

// The continued fraction cannot be evaluated with the height term at el = 0 (1/sin el); at or
// below the horizon the mapping is evaluated at this elevation (0.057 deg). Niell fitted the
// functions down to 3 deg; below that they are extrapolations.
constexpr double kNiellMinElevation_rad = 1.0e-3;

// Linear interpolation in |latitude| between the 15-degree table nodes; the end values are
// used outside [15, 75] degrees (as in Leick, section on Niell's function, and UNB3m).
double niell_interp(const std::array<double, 5>& table, double abs_lat_deg) {
  if (abs_lat_deg <= kNiellLat_deg.front()) return table.front();
  if (abs_lat_deg >= kNiellLat_deg.back()) return table.back();
  std::size_t i = 0;
  while (abs_lat_deg >= kNiellLat_deg[i + 1]) ++i;
  const double f = (abs_lat_deg - kNiellLat_deg[i]) / (kNiellLat_deg[i + 1] - kNiellLat_deg[i]);
  return table[i] + f * (table[i + 1] - table[i]);
}

// Marini (1972) continued fraction normalised to 1 at the zenith (Niell 1996; Navipedia
// "Mapping of Niell" eq. 3; the same form as the paper's "Neill" equation):
//   m(el) = (1 + a / (1 + b / (1 + c))) / (sin el + a / (sin el + b / (sin el + c)))
double marini_normalised(double sin_el, double a, double b, double c) {
  const double top = 1.0 + a / (1.0 + b / (1.0 + c));
  return top / (sin_el + a / (sin_el + b / (sin_el + c)));
}

// Day of year with its fraction, counted from January 0.0 (so 1 Jan 00:00 is 1.0), in the GPS
// time scale (Niell's UT day differs by the leap seconds, < 2e-4 day).
double fractional_day_of_year(GpsTime t) {
  const CalendarTime c = calendar_from_gps(t);
  const double seconds_of_day = c.hour * 3600.0 + c.minute * 60.0 + c.second;
  return day_of_year(c.year, c.month, c.day) + seconds_of_day / static_cast<double>(kSecondsPerDay);
}

}  // namespace

// Niell (1996) as summarised in the ESA Navipedia article "Mapping of Niell" (eqs. 1-4) and
// implemented in the UNB3m_pack (Leandro et al. 2008):
//   hydrostatic: a(phi, t) = a_avg(phi) - a_amp(phi) cos(2 pi (t - T0) / 365.25), T0 = 28,
//                with half a year added to t in the southern hemisphere; likewise b and c;
//                m_h = m(el; a, b, c) + (1/sin el - m(el; a_ht, b_ht, c_ht)) H_km
//   wet:         m_w = m(el; a_w, b_w, c_w)
// H is the height above sea level in Niell's paper; the ellipsoidal height is used (the height
// term is 0.022 per km at 5 deg, so a 50 m geoid separation moves m_h by 1.1e-3, ~2.5 mm of
// slant delay).
NiellMapping niell_mapping(const Geodetic& rx, double el_rad, GpsTime t) {
  return niell_mapping(niell_coefficients(rx, t), el_rad);
}

NiellCoefficients niell_coefficients(const Geodetic& rx, GpsTime t) {
  const double abs_lat = std::abs(rx.lat_deg);

  double doy = fractional_day_of_year(t);
  if (rx.lat_deg < 0.0) doy += kDaysPerYear / 2.0;
  const double annual = std::cos(2.0 * kPi * (doy - kNiellT0_doy) / kDaysPerYear);

  auto seasonal = [&](const std::array<double, 5>& avg, const std::array<double, 5>& amp) {
    return niell_interp(avg, abs_lat) - niell_interp(amp, abs_lat) * annual;
  };
  NiellCoefficients k;
  k.hydrostatic_a = seasonal(kNiellHydAvgA, kNiellHydAmpA);
  k.hydrostatic_b = seasonal(kNiellHydAvgB, kNiellHydAmpB);
  k.hydrostatic_c = seasonal(kNiellHydAvgC, kNiellHydAmpC);
  k.wet_a = niell_interp(kNiellWetA, abs_lat);
  k.wet_b = niell_interp(kNiellWetB, abs_lat);
  k.wet_c = niell_interp(kNiellWetC, abs_lat);
  k.h_m = rx.h_m;
  return k;
}

NiellMapping niell_mapping(const NiellCoefficients& k, double el_rad) {
  const double el = std::clamp(el_rad, kNiellMinElevation_rad, kPi / 2.0);
  const double s = std::sin(el);
  const double dm_dh_per_km = 1.0 / s - marini_normalised(s, kNiellHtA, kNiellHtB, kNiellHtC);

  NiellMapping m;
  m.hydrostatic = marini_normalised(s, k.hydrostatic_a, k.hydrostatic_b, k.hydrostatic_c) +
                  dm_dh_per_km * k.h_m / 1.0e3;
  m.wet = marini_normalised(s, k.wet_a, k.wet_b, k.wet_c);
  return m;
}

TropoDelay tropo_slant_delay(const Geodetic& rx, double el_rad, GpsTime t, const Meteo& m) {
  TropoDelay d;
  if (el_rad <= 0.0) return d;
  const TropoDelay zenith = tropo_zenith_delay(rx, m);
  const NiellMapping mf = niell_mapping(rx, el_rad, t);
  d.hydrostatic_m = zenith.hydrostatic_m * mf.hydrostatic;
  d.wet_m = zenith.wet_m * mf.wet;
  return d;
}

PierceOffset iono_pierce_offset(double el_rad) {
  const double e_sc = std::max(el_rad, 0.0) / kPi;
  const double d = 0.53 - e_sc;
  // (The cube by multiplication, as in the Klobuchar model.)
  return {(0.0137 / (e_sc + 0.11) - 0.022) * 180.0, 1.0 + 16.0 * (d * d * d)};
}

PiercePoint iono_pierce_point(const Geodetic& rx, const Direction& dir) {
  const PierceOffset o = iono_pierce_offset(dir.az_el.el_rad);
  const double lat_i = std::clamp(rx.lat_deg + o.psi_deg * dir.cos_az, -75.0, 75.0);
  return {lat_i - rx.lat_deg, o.psi_deg * dir.sin_az / std::cos(lat_i * kDegToRad), o.obliquity};
}

}  // namespace navemu
