// Size limits of the readers of user files: a file too big to be what it claims is refused
// with one line naming it, before it is read whole (RINEX, YAML, OBJ), and a CSV line without
// end is refused at the line's limit rather than read into memory. The big files are sparse:
// they take no disk space.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "emulator/numeric_csv.hpp"
#include "emulator/run_config.hpp"
#include "emulator/scene_loader.hpp"
#include "emulator/truth_csv.hpp"
#include "core/errors.hpp"
#include "emulator/rinex_files.hpp"

namespace navemu {
namespace {

namespace fs = std::filesystem;

// A file of `bytes` bytes that starts with `head` (the rest a hole).
fs::path sparse_file(const std::string& name, const std::string& head, std::uintmax_t bytes) {
  const fs::path p = fs::path(::testing::TempDir()) / ("limits_" + name);
  std::ofstream(p, std::ios::binary | std::ios::trunc) << head;
  fs::resize_file(p, bytes);
  return p;
}

template <class F>
std::string error_of(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(InputLimits, RinexFilesOver2GiBAreRefusedUnread) {
  const fs::path p = sparse_file("big.05n", "     2.10           N: GPS NAV DATA\n", (2ull << 30) + 1);
  const std::string msg = error_of([&] { (void)read_rinex_nav(p); });
  EXPECT_NE(msg.find(p.string()), std::string::npos) << msg;
  EXPECT_NE(msg.find("2147483649 bytes: over the 2 GiB"), std::string::npos) << msg;
  fs::remove(p);
}

TEST(InputLimits, YamlFilesOver16MiBAreRefusedUnread) {
  const fs::path p = sparse_file("big.yaml", "gnss: {enabled: true}\n", (16u << 20) + 1);
  const std::string msg = error_of([&] { (void)load_run_config(p); });
  EXPECT_NE(msg.find(p.string()), std::string::npos) << msg;
  EXPECT_NE(msg.find("16777217 bytes: over the 16 MiB"), std::string::npos) << msg;
  fs::remove(p);
}

TEST(InputLimits, ObjScenesOver1GiBAreRefusedUnread) {
  const fs::path p = sparse_file("big.obj", "v 0 0 0\n", (1ull << 30) + 1);
  const fs::path materials = fs::path(NAVEMU_SOURCE_DIR) / "configs" / "scenes" / "materials.yaml";
  const std::string msg = error_of([&] { (void)load_scene_mesh(p, materials); });
  EXPECT_NE(msg.find(p.string()), std::string::npos) << msg;
  EXPECT_NE(msg.find("1073741825 bytes: over the 1 GiB"), std::string::npos) << msg;
  fs::remove(p);
}

// A truth CSV whose second line never ends (a binary file, a stream without line ends): the
// reader stops at the line limit with the line's number.
TEST(InputLimits, CsvLinesOver64KiBAreRefusedAtTheLimit) {
  const fs::path p = fs::path(::testing::TempDir()) / "limits_endless.csv";
  std::ofstream(p, std::ios::binary | std::ios::trunc)
      << "time_s,lat_deg,lon_deg,h_m,v_n_mps,v_e_mps,v_d_mps,roll_deg,pitch_deg,yaw_deg\n"
      << std::string(NumericCsvReader::kMaxLineBytes + 1, '0');
  const std::string msg = error_of([&] { (void)scan_truth_csv(p.string()); });
  EXPECT_NE(msg.find(p.string() + ":2:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("line longer than 65536 bytes"), std::string::npos) << msg;

  // A line of exactly the limit is read (and then judged on its content).
  std::ofstream(p, std::ios::binary | std::ios::trunc)
      << "time_s,lat_deg,lon_deg,h_m,v_n_mps,v_e_mps,v_d_mps,roll_deg,pitch_deg,yaw_deg\n"
      << std::string(NumericCsvReader::kMaxLineBytes, '0') << "\n";
  const std::string at_limit = error_of([&] { (void)scan_truth_csv(p.string()); });
  EXPECT_EQ(at_limit.find("line longer"), std::string::npos) << at_limit;
  fs::remove(p);
}

}  // namespace
}  // namespace navemu
