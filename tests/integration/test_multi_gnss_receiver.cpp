// The receiver model tracking GPS, GLONASS, Galileo and BeiDou from a real multi-GNSS broadcast
// file, against the real receiver at that place and hour (ESBC00DNK, Septentrio PolaRx5,
// ../shared/data/gnss/esbc_20200625): satellites per system above the same mask, each system's
// pseudoranges against the real ones, and a fix with one clock per system.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "models/geodesy.hpp"
#include "models/measurement.hpp"
#include "models/orbit.hpp"
#include "models/solver.hpp"
#include "protocols/ubx.hpp"
#include "protocols/ubx_messages.hpp"
#include "tests/rinex_data.hpp"
#include "tests/test_support.hpp"

namespace navemu {
namespace {

namespace fs = std::filesystem;

constexpr double kMaskDeg = 15.0;
constexpr std::array<GnssSystem, 4> kSystems{GnssSystem::kGps, GnssSystem::kGlonass,
                                             GnssSystem::kGalileo, GnssSystem::kBeidou};

// The station's antenna reference point: marker plus 0.2160 m up (../shared/data/README.md).
Vec3 esbc_arp() {
  const Vec3 marker(3582105.2910, 532589.7313, 5232754.8054);
  return marker + R_enu_from_ecef(geodetic_from_ecef(marker)).row(2).transpose() * 0.2160;
}

// The L1 code the real file holds per system (RINEX 3.05 header of the file).
const char* l1_code(GnssSystem s) { return s == GnssSystem::kBeidou ? "C2I" : "C1C"; }
// The code of the ZED-F9P's second-band signal (GPS L2C CL, GLONASS L2OF, Galileo E5b Q, BeiDou
// B2I: band_signal(s, Band::kL2)) in the real file.
std::string l2_code(GnssSystem s) { return fmt::format("C{}", band_signal(s, Band::kL2)->id.rinex_code()); }

TEST(MultiGnssReceiver, TracksAndMeasuresEverySystemLikeTheRealReceiverAtEsbc) {
  NAVEMU_REQUIRE_SHARED();
  const NavData nav = test::rinex_nav_file(
      test::shared_data("gnss/esbc_20200625/ESBC00DNK_R_20201770000_01D_MN.rnx"));
  const ObsData obs = test::rinex_obs_file(
      test::shared_data("gnss/esbc_20200625/ESBC00DNK_R_20201770000_01H_30S_MO.rnx"));
  const Vec3 p = esbc_arp();
  const ReceiverPlace rx = receiver_place(p);

  MeasurementConfig cfg;
  cfg.seed = 7;
  cfg.elevation_mask_deg = kMaskDeg;
  for (GnssSystem s : kSystems) cfg.systems |= system_bit(s);
  apply_receiver_class(cfg, ReceiverClass::kGeodetic);
  MeasurementGenerator gen(nav, cfg);
  const SolverOptions so = gen.solver_options();

  std::map<GnssSystem, double> real_count, model_count;
  std::map<GnssSystem, std::vector<double>> pr_diff_m;  // model - real, per-epoch mean removed
  double sum_error_m = 0.0;
  int fixes = 0;
  for (const ObsEpoch& epoch : obs.epochs) {
    const EpochMeasurements e = gen.generate(epoch.time, p);
    std::map<SatId, const SatMeasurement*> model;
    for (const SatMeasurement& m : e.sats)
      if (m.dir.el_rad * kRadToDeg >= kMaskDeg) {
        model[m.sat] = &m;
        model_count[m.sat.system()] += 1.0;
      }
    std::map<GnssSystem, std::vector<double>> diffs;
    for (const SatObs& so_real : epoch.sats) {
      const std::optional<SatId> sat = so_real.sat();
      if (!sat || std::find(kSystems.begin(), kSystems.end(), sat->system()) == kSystems.end())
        continue;
      const int k = obs.header.index_of(sat->info().rinex_letter, l1_code(sat->system()));
      if (k < 0) continue;
      const double pr = so_real.values[static_cast<std::size_t>(k)];
      if (!std::isfinite(pr) || pr <= 0.0) continue;
      const BroadcastRecord r = select_record(nav, *sat, epoch.time);
      if (std::holds_alternative<std::monostate>(r)) continue;
      if (sat_geometry(r, epoch.time, rx).dir.el_rad * kRadToDeg < kMaskDeg) continue;
      real_count[sat->system()] += 1.0;
      if (const auto it = model.find(*sat); it != model.end())
        diffs[sat->system()].push_back(it->second->signals[0]->pseudorange_m - pr);
    }
    // The receivers' clocks differ: the differences of one epoch and system share them.
    for (auto& [system, d] : diffs) {
      if (d.size() < 2) continue;
      double mean = 0.0;
      for (double x : d) mean += x / static_cast<double>(d.size());
      for (double x : d) pr_diff_m[system].push_back(x - mean);
    }
    const Solution sol = solve(gen.solver_input(e), e.t_receiver, so);
    if (sol.fix == FixType::k3D) {
      ++fixes;
      sum_error_m += (sol.p_ecef_m - p).norm();
    }
  }

  const double epochs = static_cast<double>(obs.epochs.size());
  for (GnssSystem s : kSystems) {
    const double real = real_count[s] / epochs, mine = model_count[s] / epochs;
    double ss = 0.0;
    for (double x : pr_diff_m[s]) ss += x * x;
    const double rms = std::sqrt(ss / static_cast<double>(std::max<std::size_t>(pr_diff_m[s].size(), 1)));
    std::printf("%-8s above %.0f deg: %.2f satellites per epoch (real receiver %.2f); L1 pseudorange "
                "minus the real one, epoch mean removed: RMS %.2f m over %zu\n",
                system_info(s).name, kMaskDeg, mine, real, rms, pr_diff_m[s].size());
    EXPECT_GT(real, 3.0) << system_info(s).name;
    EXPECT_NEAR(mine, real, 0.2 * real) << system_info(s).name;  // the issue's +-20 %
    EXPECT_GT(pr_diff_m[s].size(), 100u) << system_info(s).name;
    EXPECT_LT(rms, 3.0) << system_info(s).name;
  }
  const double mean_error_m = sum_error_m / std::max(fixes, 1);
  std::printf("fixes %d of %zu epochs, mean 3D error %.2f m\n", fixes, obs.epochs.size(), mean_error_m);
  EXPECT_EQ(fixes, static_cast<int>(obs.epochs.size()));
  EXPECT_LT(mean_error_m, 5.0);
}

// The emulated F9P (the shipped ublox-f9p profile: five systems on L1 and L2, 10 deg mask, 32
// channels) at the station's place and hour with its broadcast file, as a logging client sees
// it: NAV-SAT's tracked satellites (C/N0 > 0) per system at the station's 30 s epochs, above the
// profile's mask, against the satellites the real receiver has L1 code for above the same mask;
// and RXM-RAWX's signals per system (L1 and L2 band) against the real receiver's codes of the
// same signals: those the part enables by default (ZED-F9P integration manual, "Default GNSS
// configuration": BeiDou B2I off, CFG-SIGNAL-BDS_B2_ENA 0), where the satellite sends them
// (only GPS Block IIR-M and later send L2C).
TEST(MultiGnssReceiver, TheEmulatedF9pTracksEachSystemLikeTheStation) {
  NAVEMU_REQUIRE_SHARED();
  const fs::path nav_file = test::shared_data("gnss/esbc_20200625/ESBC00DNK_R_20201770000_01D_MN.rnx");
  const NavData nav = test::rinex_nav_file(nav_file);
  const ObsData obs = test::rinex_obs_file(
      test::shared_data("gnss/esbc_20200625/ESBC00DNK_R_20201770000_01H_30S_MO.rnx"));
  constexpr double kF9pMaskDeg = 10.0;  // configs/gnss/ublox-f9p.yaml
  const Vec3 p = esbc_arp();
  const ReceiverPlace rx = receiver_place(p);
  const Geodetic g = geodetic_from_ecef(p);

  const fs::path dir = fs::temp_directory_path() / "navemu_f9p_esbc";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "f9p.yaml") << fmt::format(
      "scenario: {{nav: '{}'}}\ntruth: {{source: stationary, position: {{lat_deg: {:.9f}, lon_deg: {:.9f}, h_m: {:.3f}}}}}\n"
      "gnss: {{profile: ublox-f9p}}\nimu: {{enabled: false}}\n",
      nav_file.string(), g.lat_deg, g.lon_deg, g.h_m);
  const test::CommandResult r = test::run_command(
      test::shell_quote(test::navemu_binary().string()) + " simulate " + test::shell_quote((dir / "f9p.yaml").string()) +
      " --start 2020-06-25T00:00:00Z --duration 3600 --out " + test::shell_quote((dir / "out").string()) + " 2>&1");
  ASSERT_EQ(r.exit_code, 0) << r.out;

  // NAV-SAT and RXM-RAWX by GPS time of week (ms).
  std::map<std::uint32_t, ubx::NavSat> nav_sat;
  std::map<std::uint32_t, ubx::RxmRawx> rawx;
  const std::string bytes = test::read_file(dir / "out" / "ubx.bin");
  ubx::Parser parser(65535);
  parser.feed(std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()),
              [&](ubx::Parser::Result res) {
                if (res != ubx::Parser::Result::kFrame) return;
                ubx::NavSat m;
                ubx::RxmRawx raw_msg;
                if (ubx::MsgId{parser.cls(), parser.id()} == ubx::kNavSat && ubx::decode(parser.payload(), m))
                  nav_sat[m.i_tow_ms] = m;
                if (ubx::MsgId{parser.cls(), parser.id()} == ubx::kRxmRawx && ubx::decode(parser.payload(), raw_msg))
                  rawx[static_cast<std::uint32_t>(std::llround(raw_msg.rcv_tow_s * 1000.0))] = raw_msg;
              });
  ASSERT_GE(nav_sat.size(), 3590u);
  ASSERT_GE(rawx.size(), 3590u);

  std::map<GnssSystem, double> real_count, emulated_count, real_signals, emulated_signals;
  std::size_t epochs = 0;
  for (const ObsEpoch& epoch : obs.epochs) {
    const auto it = nav_sat.find(static_cast<std::uint32_t>(std::llround(to_week_tow(epoch.time).tow_s * 1000.0)));
    if (it == nav_sat.end()) continue;
    ++epochs;
    std::set<std::pair<int, int>> above;  // (gnssId, svId) tracked above the mask
    for (const ubx::NavSatSv& sv : it->second.svs)
      if (const std::optional<SatId> sat = SatId::from_ubx(sv.gnss_id, sv.sv_id);
          sat && sv.cno_dbhz > 0 && sv.elev_deg >= kF9pMaskDeg) {
        emulated_count[sat->system()] += 1.0;
        above.insert({sv.gnss_id, sv.sv_id});
      }
    // RAWX is tagged with the receiver's time (its clock is within a millisecond of GPS time).
    const auto raw = rawx.lower_bound(it->first > 5 ? it->first - 5 : 0);
    ASSERT_TRUE(raw != rawx.end() && raw->first <= it->first + 5) << it->first;
    for (const ubx::RxmRawxMeas& meas : raw->second.meas)
      if (const std::optional<SatId> sat = SatId::from_ubx(meas.gnss_id, meas.sv_id);
          sat && above.count({meas.gnss_id, meas.sv_id}))
        emulated_signals[sat->system()] += 1.0;
    for (const SatObs& so_real : epoch.sats) {
      const std::optional<SatId> sat = so_real.sat();
      if (!sat || std::find(kSystems.begin(), kSystems.end(), sat->system()) == kSystems.end()) continue;
      const int k = obs.header.index_of(sat->info().rinex_letter, l1_code(sat->system()));
      if (k < 0 || !std::isfinite(so_real.values[static_cast<std::size_t>(k)])) continue;
      const BroadcastRecord rec = select_record(nav, *sat, epoch.time);
      if (std::holds_alternative<std::monostate>(rec)) continue;
      if (sat_geometry(rec, epoch.time, rx).dir.el_rad * kRadToDeg < kF9pMaskDeg) continue;
      real_count[sat->system()] += 1.0;
      const int k2 = sat->system() == GnssSystem::kBeidou
                         ? -1
                         : obs.header.index_of(sat->info().rinex_letter, l2_code(sat->system()));
      real_signals[sat->system()] += k2 >= 0 && std::isfinite(so_real.values[static_cast<std::size_t>(k2)]) ? 2.0 : 1.0;
    }
  }
  ASSERT_GE(epochs, 110u);
  for (GnssSystem s : kSystems) {
    const double real = real_count[s] / static_cast<double>(epochs), emulated = emulated_count[s] / static_cast<double>(epochs);
    std::printf("emulated F9P at ESBC, %-8s above %.0f deg: %.2f satellites per epoch (the station %.2f)\n",
                system_info(s).name, kF9pMaskDeg, emulated, real);
    EXPECT_NEAR(emulated, real, 0.2 * real) << system_info(s).name;  // the issue's +-20 %
  }
  double real_total = 0.0, emulated_total = 0.0;
  for (GnssSystem s : kSystems) {
    const double real = real_signals[s] / static_cast<double>(epochs),
                 emulated = emulated_signals[s] / static_cast<double>(epochs);
    std::printf("emulated F9P at ESBC, %-8s above %.0f deg: %.2f signals per epoch (the station %.2f on the same signals)\n",
                system_info(s).name, kF9pMaskDeg, emulated, real);
    EXPECT_NEAR(emulated, real, 0.2 * real) << system_info(s).name;
    real_total += real;
    emulated_total += emulated;
  }
  std::printf("emulated F9P at ESBC, all: %.2f signals per epoch (the station %.2f)\n", emulated_total, real_total);
  EXPECT_NEAR(emulated_total, real_total, 0.2 * real_total);
}

// Which satellites send GPS L2C and L5 and BeiDou B2I (core/signal.cpp broadcasts(), from the
// satellites' blocks) against what the station tracks: above 15 deg, every satellite with the
// station's L1 code has C2L / C5Q / C7I exactly when broadcasts() says it is sent, but for a
// lost epoch or two.
TEST(MultiGnssReceiver, TheSatellitesThatSendEachSignalAreThoseTheStationTracks) {
  NAVEMU_REQUIRE_SHARED();
  const NavData nav = test::rinex_nav_file(
      test::shared_data("gnss/esbc_20200625/ESBC00DNK_R_20201770000_01D_MN.rnx"));
  const ObsData obs = test::rinex_obs_file(
      test::shared_data("gnss/esbc_20200625/ESBC00DNK_R_20201770000_01H_30S_MO.rnx"));
  const ReceiverPlace rx = receiver_place(esbc_arp());
  struct Check {
    SignalId signal;
    const char* code;
    int agree = 0, sent_not_tracked = 0, tracked_not_sent = 0;
    std::set<int> senders, others;
  };
  std::array<Check, 3> checks{{{kGpsL2CL, "C2L", 0, 0, 0, {}, {}}, {kGpsL5Q, "C5Q", 0, 0, 0, {}, {}}, {kBeidouB2I, "C7I", 0, 0, 0, {}, {}}}};
  for (const ObsEpoch& epoch : obs.epochs)
    for (const SatObs& so : epoch.sats) {
      const std::optional<SatId> sat = so.sat();
      if (!sat || (sat->system() != GnssSystem::kGps && sat->system() != GnssSystem::kBeidou)) continue;
      const auto has = [&](const char* code) {
        const int k = obs.header.index_of(sat->info().rinex_letter, code);
        return k >= 0 && std::isfinite(so.values[static_cast<std::size_t>(k)]);
      };
      const BroadcastRecord rec = select_record(nav, *sat, epoch.time);
      if (!has(l1_code(sat->system())) || std::holds_alternative<std::monostate>(rec) ||
          sat_geometry(rec, epoch.time, rx).dir.el_rad * kRadToDeg < kMaskDeg)
        continue;
      for (Check& c : checks) {
        if (c.signal.system != sat->system()) continue;
        const bool sent = broadcasts(*sat, c.signal, epoch.time), tracked = has(c.code);
        (sent ? c.senders : c.others).insert(sat->number());
        (sent == tracked ? c.agree : sent ? c.sent_not_tracked : c.tracked_not_sent) += 1;
      }
    }
  for (const Check& c : checks) {
    std::printf("%s: %zu satellites above %.0f deg send it, %zu do not; %d satellite-epochs agree with the "
                "station, %d sent but not tracked, %d tracked but not sent\n",
                signal_info(c.signal)->name, c.senders.size(), kMaskDeg, c.others.size(), c.agree,
                c.sent_not_tracked, c.tracked_not_sent);
    EXPECT_GE(c.senders.size(), 2u) << c.code;  // both kinds of satellite in the hour
    EXPECT_GE(c.others.size(), 2u) << c.code;
    EXPECT_GT(c.agree, 300) << c.code;
    EXPECT_EQ(c.tracked_not_sent, 0) << c.code;
    EXPECT_LE(c.sent_not_tracked, c.agree / 50) << c.code;
  }
}

// Dual frequency: every system's second signal (L2C, L2OF, E5b, B2I) and L5-band third where
// the system has one (GPS L5, Galileo E5a), on each signal's own carrier; the iono-free fix
// with each system's group delays is as good.
TEST(MultiGnssReceiver, DualFrequencySignalsOfEverySystem) {
  NAVEMU_REQUIRE_SHARED();
  const NavData nav = test::rinex_nav_file(
      test::shared_data("gnss/esbc_20200625/ESBC00DNK_R_20201770000_01D_MN.rnx"));
  MeasurementConfig cfg;
  cfg.mode = ReceiverMode::kDualFrequency;
  for (GnssSystem s : kSystems) cfg.systems |= system_bit(s);
  apply_receiver_class(cfg, ReceiverClass::kGeodetic);
  MeasurementGenerator gen(nav, cfg);
  const Vec3 p = esbc_arp();
  const GpsTime t0 = gps_from_calendar({2020, 6, 25, 0, 0, 0.0});
  std::map<GnssSystem, std::set<std::string>> signals;
  double sum_error_m = 0.0;
  for (int k = 0; k < 12; ++k) {
    const EpochMeasurements e = gen.generate(t0.plus_s(300.0 * k), p);
    for (const SatMeasurement& m : e.sats) {
      for (const auto& so : m.signals) {
        if (!so) continue;
        signals[m.sat.system()].insert(so->signal.rinex_code());
        const double expected_hz = carrier_frequency_hz(so->signal, m.glonass_channel);
        EXPECT_EQ(so->carrier_hz, expected_hz);
      }
    }
    const Solution sol = solve(gen.solver_input(e), e.t_receiver, gen.solver_options());
    ASSERT_EQ(sol.fix, FixType::k3D);
    sum_error_m += (sol.p_ecef_m - p).norm();
  }
  std::printf("iono-free fixes of four systems: mean 3D error %.2f m\n", sum_error_m / 12.0);
  EXPECT_LT(sum_error_m / 12.0, 3.0);
  EXPECT_EQ(signals[GnssSystem::kGps], (std::set<std::string>{"1C", "2L", "5Q"}));
  EXPECT_EQ(signals[GnssSystem::kGalileo], (std::set<std::string>{"1C", "7Q", "5Q"}));
  EXPECT_EQ(signals[GnssSystem::kBeidou], (std::set<std::string>{"2I", "7I"}));
  EXPECT_EQ(signals[GnssSystem::kGlonass], (std::set<std::string>{"1C", "2C"}));
}

// `navemu obs` with four systems: RTKLIB's rnx2rtkp reads the mixed RINEX 3 file (GLONASS
// slots and channels in its header) and solves it with all four systems near the truth.
TEST(MultiGnssReceiver, RtklibSolvesNavemusFourSystemObservationFile) {
  NAVEMU_REQUIRE_SHARED();
  const auto nav = test::shared_data("gnss/esbc_20200625/ESBC00DNK_R_20201770000_01D_MN.rnx");
  const auto dir = std::filesystem::path(::testing::TempDir()) / "navemu_multi_gnss_obs";
  std::filesystem::create_directories(dir);
  const Vec3 truth = esbc_arp();
  const Geodetic g = geodetic_from_ecef(truth);
  const auto obs = dir / "esbc_synth.rnx", pos = dir / "esbc_synth.pos";
  const auto made = test::run_command(
      test::shell_quote(test::navemu_binary().string()) + " obs --nav " + test::shell_quote(nav) +
      " --systems G,R,E,C --receiver geodetic --seed 3 --start 2020-06-25T00:00:00Z --duration 3600"
      " --interval 30 --at " + std::to_string(g.lat_deg) + "," + std::to_string(g.lon_deg) + "," +
      std::to_string(g.h_m) + " --out " + test::shell_quote(obs) + " 2>/dev/null");
  ASSERT_EQ(made.exit_code, 0);
  {
    std::ofstream conf(dir / "spp.conf");
    conf << "pos1-posmode=single\npos1-elmask=15\npos1-ionoopt=brdc\npos1-tropopt=saas\n"
            "pos1-navsys=45\n";
  }
  std::filesystem::remove(pos);
  const auto rtk = test::run_command("rnx2rtkp -k " + test::shell_quote(dir / "spp.conf") + " -e -o " +
                                     test::shell_quote(pos) + " " + test::shell_quote(obs) + " " +
                                     test::shell_quote(nav) + " 2>/dev/null");
  ASSERT_EQ(rtk.exit_code, 0) << "rnx2rtkp (Debian package rtklib) missing or failed";
  const std::vector<test::RtklibFix> sol = test::read_rtklib_ecef_pos(pos);
  double sum_m = 0.0;
  for (const test::RtklibFix& fix : sol) sum_m += (fix.p_ecef_m - truth).norm();
  const double mean_m = sum_m / static_cast<double>(std::max<std::size_t>(sol.size(), 1));
  std::printf("rnx2rtkp (GPS, GLONASS, Galileo, BeiDou) on navemu's file: %zu of 121 epochs, "
              "mean 3D error %.2f m\n", sol.size(), mean_m);
  EXPECT_EQ(sol.size(), 121u);
  EXPECT_LT(mean_m, 3.0);  // the end-to-end bound
}

// Systems switched off and on while running (u-blox CFG-SIGNAL): the satellites go at once and
// come back after the re-acquisition time, on a new carrier arc.
TEST(MultiGnssReceiver, SystemsSwitchedOffAndOnWhileRunning) {
  NAVEMU_REQUIRE_SHARED();
  const NavData nav = test::rinex_nav_file(
      test::shared_data("gnss/esbc_20200625/ESBC00DNK_R_20201770000_01D_MN.rnx"));
  MeasurementConfig cfg;
  for (GnssSystem s : kSystems) cfg.systems |= system_bit(s);
  MeasurementGenerator gen(nav, cfg);
  const Vec3 p = esbc_arp();
  const GpsTime t0 = gps_from_calendar({2020, 6, 25, 0, 0, 0.0});
  const auto galileo_at = [&](double t_s) {
    int n = 0;
    bool new_arcs = true;
    for (const SatMeasurement& m : gen.generate(t0.plus_s(t_s), p).sats)
      if (m.sat.system() == GnssSystem::kGalileo) {
        ++n;
        new_arcs = new_arcs && m.signals[0]->loss_of_lock;
      }
    return std::make_pair(n, new_arcs);
  };
  const int before = galileo_at(0.0).first;
  EXPECT_GE(before, 5);
  EXPECT_FALSE(galileo_at(0.2).second) << "continuing arcs";
  gen.set_active_systems(~system_bit(GnssSystem::kGalileo));
  EXPECT_EQ(galileo_at(0.4).first, 0);
  gen.set_active_systems(~0u);
  EXPECT_EQ(galileo_at(0.6).first, 0) << "re-acquiring (TrackingParams::reacquisition_s 1 s)";
  const auto back = galileo_at(1.6);
  EXPECT_EQ(back.first, before);
  EXPECT_TRUE(back.second) << "new carrier arcs";
}

}  // namespace
}  // namespace navemu
