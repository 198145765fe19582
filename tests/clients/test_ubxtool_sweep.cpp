// tools/ubxtool-sweep in CI: gpsd's unmodified ubxtool against `navemu run` with each u-blox
// profile on a pty configured `port: usb`. A shortened sweep (the first 40 presets of ubxtool's
// table that apply to the profile's protocol version and the first 160 of its keys, about 30 s
// per profile) must meet the thresholds below, and every value set must read back and survive
// (or not) a CFG-CFG save and a cold start as on the part. Each preset's answer is compared with
// the one the part gives by its interface description (the sweep's PART_MESSAGES): the floor is
// what this sweep measures, so that anything the device stops answering, or answers where the
// part does not, fails. The full sweep (`tools/ubxtool-sweep --profile ...` without --subset)
// reports what it still lacks.

#include <gtest/gtest.h>

#include <fmt/format.h>

#include "tests/clients/client_support.hpp"

namespace navemu::test::clients {
namespace {

struct SweepCase {
  const char* profile;
  double min_presets_pct;  // of the presets swept, answered (the polled message or ACK-ACK)
  double min_as_part_pct;  // of the presets swept, answered as the part answers them
  double min_valget_pct;   // of ubxtool's keys the F9P has, answered by CFG-VALGET
};

class UbxtoolSweep : public ::testing::TestWithParam<SweepCase> {};

TEST_P(UbxtoolSweep, ShortSweepMeetsItsThresholds) {
  const std::string ubxtool = find_program("ubxtool");
  if (ubxtool.empty()) GTEST_SKIP() << "ubxtool not found: install Debian's python3-gps 3.22 (gpsd-clients)";
  const SweepCase& c = GetParam();
  TempDir dir("ubxtool-sweep");
  const fs::path out = dir / "sweep.out";
  Child sweep({"/usr/bin/python3", (fs::path(NAVEMU_SOURCE_DIR) / "tools" / "ubxtool-sweep").string(), "--profile",
               (fs::path(NAVEMU_SOURCE_DIR) / "configs" / "gnss" / c.profile).string(), "--navemu",
               navemu_binary().string(), "--subset", "40", "--min-presets", fmt::format("{}", c.min_presets_pct),
               "--min-as-part", fmt::format("{}", c.min_as_part_pct), "--min-valget",
               fmt::format("{}", c.min_valget_pct), "--require-checks"},
              out, out);
  const auto st = sweep.wait_exit(120.0);
  sweep.stop();
  const std::string text = slurp(out);
  EXPECT_TRUE(st && WIFEXITED(*st) && WEXITSTATUS(*st) == 0) << describe_status(st) << "\n" << text;
  // The summary, for the log.
  const auto runs = text.find(" ubxtool runs in ");
  const auto at = runs == std::string::npos ? 0 : text.rfind('\n', runs) + 1;
  std::printf("%s", text.substr(at).c_str());
}

INSTANTIATE_TEST_SUITE_P(Profiles, UbxtoolSweep,
                         // Every preset as the part answers it (the M8's first 40 presets
                         // include its five AID polls; the F9P's NAK the CFG messages it lacks).
                         ::testing::Values(SweepCase{"ublox-m8.yaml", 60.0, 100.0, 0},
                                           SweepCase{"ublox-f9p.yaml", 50.0, 100.0, 95.0},
                                           SweepCase{"ublox-f9p-hpg132.yaml", 50.0, 100.0, 95.0}),
                         [](const ::testing::TestParamInfo<SweepCase>& p) {
                           std::string n = p.param.profile;
                           n = n.substr(0, n.find('.'));
                           for (char& ch : n)
                             if (ch == '-') ch = '_';
                           return n;
                         });

}  // namespace
}  // namespace navemu::test::clients
