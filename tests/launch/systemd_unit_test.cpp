// config/systemd/cover-vehicle@.service: the unit that starts a vehicle's launch at boot.
// systemd-analyze verify (Debian's systemd package) parses an instance of it whose
// ExecStart names this build's cover-launch, and must find nothing to say; the keys the
// ordered stop and the restart policy depend on are checked as text.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

#include "cover/process/scoped_setup.hpp"
#include "cover/test/file_contents.hpp"
#include "cover/test/scratch_dir.hpp"

namespace {

namespace fs = std::filesystem;

const std::string kUnit = std::string(COVER_SOURCE_DIR) + "/config/systemd/cover-vehicle@.service";
constexpr const char* kInstalledLauncher = "/opt/cover/bin/cover-launch";

using cover::test::read_text;

bool has_line(const std::string& text, const std::string& line) {
  std::istringstream lines(text);
  for (std::string each; std::getline(lines, each);) {
    if (each == line) return true;
  }
  return false;
}

std::optional<std::string> find_program(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(std::string(path ? path : "") + ":/usr/bin:/bin");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const fs::path candidate = fs::path(dir) / name;
    if (!dir.empty() && access(candidate.c_str(), X_OK) == 0) return candidate.string();
  }
  return std::nullopt;
}

TEST(SystemdUnit, StartsTheVehiclesLaunchAndStopsItInOrder) {
  const std::string unit = read_text(kUnit);
  ASSERT_FALSE(unit.empty()) << kUnit;
  // One launch file per instance; the launcher finds the other executables beside itself.
  EXPECT_TRUE(
      has_line(unit, std::string("ExecStart=") + kInstalledLauncher + " /etc/cover/%i.yaml"));
  EXPECT_EQ(fs::path(COVER_LAUNCH).filename(), fs::path(kInstalledLauncher).filename());
  EXPECT_TRUE(has_line(unit, "After=network-online.target"));
  EXPECT_TRUE(has_line(unit, "Wants=network-online.target"));
  EXPECT_TRUE(has_line(unit, "User=cover"));
  EXPECT_TRUE(has_line(unit, "Environment=COVER_DDS_PROFILE=wifi"));
  EXPECT_TRUE(has_line(unit, "Restart=on-failure"));
  // SIGINT to the launcher alone: it stops its processes in reverse start order.
  EXPECT_TRUE(has_line(unit, "KillSignal=SIGINT"));
  EXPECT_TRUE(has_line(unit, "KillMode=mixed"));
  EXPECT_TRUE(has_line(unit, "TimeoutStopSec=60"));
  EXPECT_TRUE(has_line(unit, "SuccessExitStatus=130")) << "an operator's stop is no failure";
  EXPECT_TRUE(has_line(unit, "WantedBy=multi-user.target"));
}

TEST(SystemdUnit, SystemdAnalyzeVerifiesAnInstance) {
  const auto analyze = find_program("systemd-analyze");
  if (!analyze) GTEST_SKIP() << "systemd-analyze not installed: only the text checks ran";
  std::string unit = read_text(kUnit);
  const auto at = unit.find(kInstalledLauncher);
  ASSERT_NE(at, std::string::npos);
  unit.replace(at, std::string(kInstalledLauncher).size(), COVER_LAUNCH);
  // The instance name is the file's: cover-vehicle@uav0.service runs /etc/cover/uav0.yaml.
  const std::string instance = cover::test::scratch_path("cover-vehicle@uav0.service");
  std::ofstream(instance) << unit;
  const auto result = cover::process::run_command({*analyze, "verify", instance},
                                                  cover::test::scratch_path("verify.log"),
                                                  std::chrono::seconds(60));
  EXPECT_EQ(result.exit_code, 0) << result.output;
  EXPECT_EQ(result.output, "") << "systemd-analyze has something to say about the unit";
}

}  // namespace
