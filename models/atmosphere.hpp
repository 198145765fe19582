#pragma once
// Atmospheric propagation delays on the GPS L1 signal.

#include "core/nav_data.hpp"
#include "core/signal.hpp"
#include "core/time.hpp"
#include "models/geodesy.hpp"

namespace navemu {

inline constexpr double kGpsL1_Hz = carrier_frequency_hz(kGpsL1CA);
inline constexpr double kGpsL2_Hz = carrier_frequency_hz(kGpsL2CL);
inline constexpr double kGpsL5_Hz = carrier_frequency_hz(kGpsL5Q);

// Klobuchar single-frequency ionospheric delay on L1, in seconds (IS-GPS-200 20.3.3.5.2.5,
// Figure 20-4). Scale by (f_L1/f)^2 for other frequencies.
double klobuchar_delay_l1_s(const KlobucharCoefficients& k, const Geodetic& rx, const AzEl& dir,
                            GpsTime t);
// The same with the GPS time of week of t (to_week_tow(t).tow_s) computed once for many
// satellites of an epoch.
double klobuchar_delay_l1_s(const KlobucharCoefficients& k, const Geodetic& rx, const AzEl& dir,
                            double gps_tow_s);
// The same with the azimuth's sine and cosine known (direction()).
double klobuchar_delay_l1_s(const KlobucharCoefficients& k, const Geodetic& rx, const Direction& dir,
                            double gps_tow_s);

// Ionospheric pierce point offset from the receiver and the obliquity factor, with the
// single-layer geometry of IS-GPS-200 20.3.3.5.2.5 (Figure 20-4): earth-centred angle
// psi = 0.0137 / (E + 0.11) - 0.022 semicircles, F = 1 + 16 (0.53 - E)^3.
struct PiercePoint {
  double dlat_deg = 0.0;
  double dlon_deg = 0.0;
  double obliquity = 1.0;
};
PiercePoint iono_pierce_point(const Geodetic& rx, const Direction& dir);
// Of that geometry, what depends on the elevation alone: psi (degrees) and F.
struct PierceOffset {
  double psi_deg = 0.0;
  double obliquity = 1.0;
};
PierceOffset iono_pierce_offset(double el_rad);

// Surface meteorology at the receiver.
struct Meteo {
  double pressure_hpa = 1013.25;
  double temperature_k = 288.15;
  double relative_humidity = 0.5;  // 0..1
};
// Standard atmosphere at an ellipsoidal height (the model RTKLIB and most receivers use:
// 1013.25 hPa and 15 degC at sea level, humidity given).
Meteo standard_atmosphere(double h_m, double relative_humidity = 0.7);

struct TropoDelay {
  double hydrostatic_m = 0.0;
  double wet_m = 0.0;
  double total_m() const { return hydrostatic_m + wet_m; }
};

// Saastamoinen slant delay with the 1/cos(z) mapping (Saastamoinen 1972; the form RTKLIB's
// tropmodel uses, hydrostatic zenith delay after Davis et al. 1985).
TropoDelay saastamoinen_delay(const Geodetic& rx, double el_rad, const Meteo& m);
// The same in two parts, the first depending only on the receiver and the meteorology (once
// per position for many satellites): the zenith delays (delay = zenith / cos z), and whether
// the height lies in RTKLIB's domain.
inline constexpr double kSaastamoinenLowest_m = -100.0;  // RTKLIB's domain: [-100 m, 10 km]
struct SaastamoinenZenith {
  bool in_domain = false;
  double hydrostatic_m = 0.0;
  double wet_m = 0.0;
};
SaastamoinenZenith saastamoinen_zenith(const Geodetic& rx, const Meteo& m);
TropoDelay saastamoinen_delay(const SaastamoinenZenith& zenith, double el_rad);

// ---- Ionosphere, first-order (issue: GNSS error physics) -----------------------------------

// Zenith group delay of a vertical total electron content at a carrier frequency:
// 40.3 TEC / f^2 (TEC in electrons/m^2; 1 TECU = 1e16). Code is delayed, carrier advanced.
double iono_zenith_delay_m(double vtec_tecu, double freq_hz);

// The paper's ionospheric mapping (Durst & Goodin, section 2.1, after Montenbruck):
// 2.037 / (sqrt(sin^2 el + 0.076) + sin el): 0.99985 at the zenith, 3.20 at 15 deg, 4.08 at
// 10 deg and 2.037 / sqrt(0.076) = 7.389 at the horizon (the slant-to-vertical ratio of a
// ~240 km thick layer starting at the ground, not of a thin shell at 350 km, which gives ~3 at
// the horizon). Negative elevations are taken as the horizon.
double iono_paper_mapping(double el_rad);

// The vertical total electron content of the paper's validation runs (section 3: "VTEC set
// at 12"), TECU.
inline constexpr double kPaperValidationVtec_tecu = 12.0;

// Scales an L1 ionospheric delay to another frequency: (f_L1 / f)^2.
double iono_scale_from_l1(double delay_l1, double freq_hz);

// ---- Troposphere with meteorology and Niell mapping ----------------------------------------

// Saturation water-vapour pressure over water, hPa, at a temperature in K: the Magnus-type
// law 6.108 exp((17.15 T - 4684) / (T - 38.45)) that RTKLIB's tropmodel (and
// saastamoinen_delay) uses.
double saturation_vapour_pressure_hpa(double temperature_k);
// Water-vapour partial pressure e = RH e_s(T), hPa.
double water_vapour_pressure_hpa(const Meteo& m);

// Zenith delays from surface meteorology: hydrostatic after Saastamoinen in the form of
// Davis et al. (1985) (the paper's Park & Ha form), wet after Saastamoinen (1972).
TropoDelay tropo_zenith_delay(const Geodetic& rx, const Meteo& m);

// Niell (1996) mapping functions: hydrostatic (latitude and day-of-year tables, with the
// height correction) and wet (latitude table).
struct NiellMapping {
  double hydrostatic = 1.0;
  double wet = 1.0;
};
NiellMapping niell_mapping(const Geodetic& rx, double el_rad, GpsTime t);
// The same in two parts: the coefficients, which depend only on the receiver's latitude and
// height and the day of year (once per epoch for every satellite), and the mapping at an
// elevation.
struct NiellCoefficients {
  // Seasonal, at the latitude.
  double hydrostatic_a = 0.0, hydrostatic_b = 0.0, hydrostatic_c = 0.0;
  double wet_a = 0.0, wet_b = 0.0, wet_c = 0.0;
  double h_m = 0.0;  // ellipsoidal height, for the hydrostatic height correction
};
NiellCoefficients niell_coefficients(const Geodetic& rx, GpsTime t);
NiellMapping niell_mapping(const NiellCoefficients& k, double el_rad);

// Slant delay: zenith delays from `m` mapped with Niell. Zero below the horizon.
TropoDelay tropo_slant_delay(const Geodetic& rx, double el_rad, GpsTime t, const Meteo& m);

}  // namespace navemu
