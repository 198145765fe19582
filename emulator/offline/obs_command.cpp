// navemu obs: a static receiver's synthetic RINEX 3 observation file from the physics-based
// measurement generator.

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <ostream>

#include "emulator/commands.hpp"
#include "core/errors.hpp"
#include "models/measurement.hpp"
#include "protocols/rinex_writer.hpp"

namespace navemu {

namespace {

const std::map<std::string, ReceiverMode> kModes = {{"standalone", ReceiverMode::kStandalone},
                                                    {"dual", ReceiverMode::kDualFrequency},
                                                    {"dgps", ReceiverMode::kDgps},
                                                    {"rtk", ReceiverMode::kRtkFixed}};

// RINEX signal strength indicator from C/N0 (RINEX 3.04 section 5.7: 1..9, 6 dB steps).
int ssi_from_cn0(double cn0_dbhz) {
  return std::clamp(static_cast<int>(std::floor(cn0_dbhz / 6.0)), 1, 9);
}


}  // namespace

void add_obs_command(CLI::App& app, ObsOptions& opt) {
  CLI::App* obs = app.add_subcommand(
      "obs", "Synthetic RINEX 3 observation file of a static receiver (physics-based errors)");
  obs->footer(
      "Generates what a receiver at --at measures every --interval seconds for --duration seconds\n"
      "from --start: pseudorange, carrier phase, Doppler and C/N0 on L1 C/A (C1C L1C D1C S1C), plus\n"
      "L2C and L5 (C2L.. C5Q..) in dual-frequency mode. Every error term evolves in time from its\n"
      "own seeded random stream: the same seed gives a byte-identical file.\n"
      "Error sources (each can be disabled): iono (broadcast Klobuchar or the paper's VTEC model,\n"
      "with the model's error), tropo (Saastamoinen + Niell with the given meteorology), satellite\n"
      "(broadcast orbit and clock errors), clock (receiver oscillator), noise (DLL/PLL/FLL thermal\n"
      "noise from C/N0), multipath (statistical code multipath).\n"
      "Modes: standalone (raw L1), dual (raw L1/L2/L5), dgps and rtk (C1C holds the pseudorange\n"
      "after differential correction: process it without iono/tropo corrections).\n"
      "--systems adds the other systems (of a mixed --nav file, or built in), each with its own\n"
      "signals: GLONASS L1OF/L2OF (C1C, C2C), Galileo E1/E5b/E5a (C1C, C7Q, C5Q), BeiDou B1I/B2I\n"
      "(C2I, C7I), QZSS as GPS.\n"
      "Example:\n"
      "  navemu obs --nav 07590920.05n --at 35.1609,139.6138,68.4 --start 2005-04-01T23:59:47Z \\\n"
      "      --duration 3600 --interval 30 --out synth.rnx --seed 7");
  auto* nav = obs->add_option("--nav", opt.nav_file, "RINEX navigation file (2.x, 3.x, 4.x)");
  obs->add_flag("--nominal", opt.nominal, "Use the built-in nominal constellation (default)")
      ->excludes(nav);
  obs->add_option("--at", opt.at, "Receiver LAT,LON,H (deg, deg, m above the WGS-84 ellipsoid)")
      ->capture_default_str();
  obs->add_option("--start", opt.start,
                  "First epoch: ISO-8601 UTC (2023-01-08T09:59:42Z) or GPS WEEK:TOW")
      ->required();
  obs->add_option("--duration", opt.duration_s, "Length in seconds")
      ->capture_default_str()
      ->check(number_between(0.0, 7.0 * 86400.0));
  obs->add_option("--interval", opt.interval_s, "Epoch interval in seconds")
      ->capture_default_str()
      ->check(number_between(0.001, 3600.0));
  obs->add_option("--out", opt.out_file, "Output RINEX 3 observation file")->required();
  obs->add_option("--systems", opt.systems,
                  "Systems, RINEX letters separated by commas: G GPS, R GLONASS, E Galileo, "
                  "C BeiDou, J QZSS")
      ->delimiter(',')
      ->capture_default_str()
      ->check(CLI::IsMember({"G", "R", "E", "C", "J"}));
  obs->add_option("--mode", opt.mode, "Receiver mode")
      ->capture_default_str()
      ->check(CLI::IsMember({"standalone", "dual", "dgps", "rtk"}));
  obs->add_option("--receiver", opt.receiver,
                  "Receiver class: consumer (1-chip correlator, 1 Hz code loop, patch antenna) or "
                  "geodetic (0.1-chip correlator, 0.1 Hz carrier-aided code loop, choke ring)")
      ->capture_default_str()
      ->check(CLI::IsMember({"consumer", "geodetic"}));
  obs->add_option("--sisre", opt.sisre_m,
                  "Signal-in-space range error of the broadcast orbits and clocks, m RMS "
                  "(default 0.56, GPS of recent years; roughly 0.6-1 in the mid-2000s)")
      ->check(number_between(0.0, 100.0));
  obs->add_option("--sat-errors", opt.sat_errors,
                  "Broadcast orbit/clock error model: gauss-markov (radial/along/cross and clock, "
                  "correlated in time) or paper (the paper's Hwang-Parkinson formula, ~10 m)")
      ->capture_default_str()
      ->check(CLI::IsMember({"gauss-markov", "paper"}));
  obs->add_option("--clock-h0", opt.clock_h0,
                  "Receiver oscillator white-frequency coefficient h0 (default 2e-19, a TCXO)")
      ->check(number_between(0.0, 1e-15));
  obs->add_option("--clock-h-2", opt.clock_h_minus2,
                  "Receiver oscillator random-walk-frequency coefficient h-2 (default 2e-20)")
      ->check(number_between(0.0, 1e-15));
  obs->add_option("--seed", opt.seed, "Scenario seed")->capture_default_str();
  obs->add_option("--disable", opt.disable, "Error sources to switch off (comma-separated)")
      ->delimiter(',')
      ->check(CLI::IsMember({"iono", "tropo", "satellite", "clock", "noise", "multipath"}));
  obs->add_option("--iono", opt.iono,
                  "Ionosphere model: klobuchar (the nav file's; vtec when it has none) or vtec")
      ->capture_default_str()
      ->check(CLI::IsMember({"klobuchar", "vtec"}));
  obs->add_option("--vtec", opt.vtec_tecu, "Vertical TEC for --iono vtec, TECU")
      ->capture_default_str()
      ->check(number_between(0.0, 500.0));
  obs->add_option("--pressure-hpa", opt.pressure_hpa, "Surface pressure (default: standard atmosphere)")
      ->check(number_between(300.0, 1100.0));
  obs->add_option("--temperature-c", opt.temperature_c, "Surface temperature")
      ->check(number_between(-80.0, 60.0));
  obs->add_option("--humidity", opt.humidity, "Relative humidity, 0..1")
      ->check(number_between(0.0, 1.0));
}

int run_obs(const ObsOptions& opt, std::ostream& out, std::ostream& err) {
  (void)out;
  const GpsTime start = time_option(opt.start, "--start");
  const Geodetic rx = parse_geodetic(opt.at, "--at");
  const Vec3 p_rx = ecef_from_geodetic(rx);
  MeasurementConfig cfg;
  cfg.mode = kModes.at(opt.mode);
  apply_receiver_class(cfg, opt.receiver == "geodetic" ? ReceiverClass::kGeodetic
                                                       : ReceiverClass::kConsumer);
  cfg.seed = opt.seed;
  cfg.systems = 0;
  for (const GnssSystemInfo& i : kGnssSystems)
    if (std::find(opt.systems.begin(), opt.systems.end(), std::string(1, i.rinex_letter)) != opt.systems.end())
      cfg.systems |= system_bit(i.system);
  const NavData nav = load_nav_or_nominal(opt.nav_file, start, cfg.systems);
  require_nav_coverage(nav, start, start.plus_s(opt.duration_s), {});
  if (opt.sisre_m) cfg.sat_errors = cfg.sat_errors.scaled_to_sisre(*opt.sisre_m);
  if (opt.sat_errors == "paper") cfg.sat_error_model = SatErrorModel::kPaper;
  if (opt.clock_h0) cfg.clock.h0 = *opt.clock_h0;
  if (opt.clock_h_minus2) cfg.clock.h_minus2 = *opt.clock_h_minus2;
  cfg.iono_model = opt.iono == "vtec" ? IonoModel::kPaperVtec : IonoModel::kKlobuchar;
  cfg.vtec_tecu = opt.vtec_tecu;
  for (const std::string& d : opt.disable) {
    if (d == "iono") cfg.errors.ionosphere = false;
    if (d == "tropo") cfg.errors.troposphere = false;
    if (d == "satellite") cfg.errors.satellite = false;
    if (d == "clock") cfg.errors.receiver_clock = false;
    if (d == "noise") cfg.errors.noise = false;
    if (d == "multipath") cfg.errors.multipath = false;
  }
  if (opt.pressure_hpa || opt.temperature_c || opt.humidity) {
    Meteo m = standard_atmosphere(std::max(rx.h_m, 0.0), 0.5);
    if (opt.pressure_hpa) m.pressure_hpa = *opt.pressure_hpa;
    if (opt.temperature_c) m.temperature_k = *opt.temperature_c + 273.15;
    if (opt.humidity) m.relative_humidity = *opt.humidity;
    cfg.meteo = m;
  }
  MeasurementGenerator gen(nav, cfg);
  const bool raw_dual = cfg.mode == ReceiverMode::kDualFrequency;
  const int n_bands = raw_dual ? 3 : 1;

  ObsHeader h;
  h.version = 3.04;
  // Per system and band: pseudorange, carrier phase, Doppler and C/N0 of the system's signal
  // there (RINEX 3.04 section 5.1: C1C L1C D1C S1C for GPS L1 C/A, C2L.. for L2C (L), C5Q..
  // for the L5 pilot; band_signal for the other systems).
  for (const GnssSystemInfo& i : kGnssSystems) {
    if (!(cfg.systems & system_bit(i.system))) continue;
    for (int b = 0; b < n_bands; ++b)
      if (const std::optional<BandSignal> s = band_signal(i.system, static_cast<Band>(b)))
        for (const char type : {'C', 'L', 'D', 'S'}) h.types[i.rinex_letter].push_back(type + s->id.rinex_code());
  }
  h.file_system = h.types.size() == 1 ? h.types.begin()->first : 'M';
  h.marker_name = "NAVEMU";
  h.approx_position_ecef_m = p_rx;
  h.interval_s = opt.interval_s;
  h.leap_seconds = leap_seconds_at_gps(start, nav.leap_seconds);

  ObsWriterInfo info;
  std::vector<ObsEpoch> epochs;
  const auto n_epochs = static_cast<long long>(std::floor(opt.duration_s / opt.interval_s + 1e-9)) + 1;
  std::size_t n_obs = 0;
  for (long long k = 0; k < n_epochs; ++k) {
    const GpsTime t = start.plus_s(static_cast<double>(k) * opt.interval_s);
    const EpochMeasurements e = gen.generate(t, p_rx);
    ObsEpoch oe;
    oe.time = e.t_receiver;  // the receiver clock's tick (RINEX 3.04: epochs are receiver clock time)
    for (const SatMeasurement& m : e.sats) {
      SatObs so;
      so.system = m.sat.info().rinex_letter;
      so.number = m.sat.number();
      if (m.sat.system() == GnssSystem::kGlonass)
        info.glonass_frequency_numbers[m.sat.number()] = m.glonass_channel;
      for (int b = 0; b < n_bands; ++b) {
        if (!band_signal(m.sat.system(), static_cast<Band>(b))) continue;
        const auto& s = m.signals[static_cast<std::size_t>(b)];
        const bool corrected = b == 0 && !raw_dual && cfg.mode != ReceiverMode::kStandalone;
        const int ssi = s ? ssi_from_cn0(s->cn0_dbhz) : 0;
        so.values.push_back(s ? (corrected ? m.engine_pseudorange_m : s->pseudorange_m) : kMissing);
        so.values.push_back(s ? s->carrier_cycles : kMissing);
        so.values.push_back(s ? s->doppler_hz : kMissing);
        so.values.push_back(s ? s->cn0_dbhz : kMissing);
        so.lli.insert(so.lli.end(), {0, s && s->loss_of_lock ? 1 : 0, 0, 0});
        so.ssi.insert(so.ssi.end(), {ssi, ssi, 0, 0});
      }
      n_obs += 1;
      oe.sats.push_back(std::move(so));
    }
    epochs.push_back(std::move(oe));
  }

  info.comments = {
      fmt::format("navemu obs: mode {}, seed {}", opt.mode, opt.seed),
      fmt::format("nav: {}", nav.source.substr(0, 50)),
  };
  if (!opt.disable.empty()) {
    std::string list;
    for (const std::string& d : opt.disable) list += (list.empty() ? "" : ",") + d;
    info.comments.push_back("disabled: " + list);
  }
  // PGM / RUN BY / DATE carries the scenario's start, not the wall clock: reproducible files.
  const CalendarTime d = utc_from_gps(start);
  info.date = fmt::format("{:04}{:02}{:02} {:02}{:02}{:02} UTC", d.year, d.month, d.day, d.hour,
                          d.minute, static_cast<int>(d.second));
  std::ofstream file(opt.out_file, std::ios::binary);
  if (!file) throw InputError(opt.out_file, 0, "--out", "cannot open for writing");
  write_rinex3_obs(file, h, epochs, info);
  file.close();
  if (!file) throw InputError(opt.out_file, 0, "--out", "write failed (disk full?)");
  fmt::print(err, "navemu obs: wrote {} epochs, {} satellite observations to {} (mode {}, seed {})\n",
             epochs.size(), n_obs, opt.out_file, opt.mode, opt.seed);
  return 0;
}

}  // namespace navemu
