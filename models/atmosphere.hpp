#pragma once
// Atmospheric propagation delays on the GPS L1 signal.

#include "models/ephemeris.hpp"
#include "models/geodesy.hpp"
#include "models/time.hpp"

namespace navemu {

inline constexpr double kGpsL1_Hz = 1575.42e6;
inline constexpr double kGpsL2_Hz = 1227.60e6;
inline constexpr double kGpsL5_Hz = 1176.45e6;

// Klobuchar single-frequency ionospheric delay on L1, in seconds (IS-GPS-200 20.3.3.5.2.5,
// Figure 20-4). Scale by (f_L1/f)^2 for other frequencies.
double klobuchar_delay_l1_s(const KlobucharCoefficients& k, const Geodetic& rx, const AzEl& dir,
                            GpsTime t);

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

}  // namespace navemu
