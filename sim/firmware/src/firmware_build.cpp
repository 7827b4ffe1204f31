#include "cover/firmware/firmware_build.hpp"

#include <unistd.h>

#include <cstdlib>
#include <vector>

namespace cover::firmware {
namespace {

namespace fs = std::filesystem;

constexpr const char* kHowTo =
    " (docs/flight-controller.md, \"The real firmware in the loop\", shows how to build it)";

std::string env(const char* name) {
  const char* value = std::getenv(name);
  return value != nullptr ? value : "";
}

bool executable(const fs::path& path) {
  return fs::is_regular_file(path) && ::access(path.c_str(), X_OK) == 0;
}

FirmwareLookup missing(std::string why) {
  return {std::nullopt, std::move(why) + kHowTo};
}

}  // namespace

FirmwareLookup find_px4_sitl() {
  const std::string dir = env("COVER_PX4_SITL");
  if (dir.empty()) {
    return missing(
        "no PX4 SITL: set COVER_PX4_SITL to a PX4 SITL build directory (PX4's "
        "build/px4_sitl_default, holding bin/px4 and etc/)");
  }
  const fs::path root = fs::absolute(dir);
  FirmwareBuild build{root / "bin" / "px4", root / "etc"};
  if (!executable(build.binary)) {
    return missing("COVER_PX4_SITL=" + dir + " holds no executable bin/px4");
  }
  if (!fs::is_regular_file(build.data / "init.d-posix" / "rcS")) {
    return missing("COVER_PX4_SITL=" + dir + " holds no etc/init.d-posix/rcS (PX4's ROMFS)");
  }
  return {build, ""};
}

FirmwareLookup find_arducopter_sitl() {
  const std::string dir = env("COVER_ARDUPILOT_SITL");
  if (dir.empty()) {
    return missing(
        "no ArduCopter SITL: set COVER_ARDUPILOT_SITL to an ArduPilot SITL build directory "
        "(ArduPilot's build/sitl, holding bin/arducopter)");
  }
  const fs::path root = fs::absolute(dir);
  const fs::path binary = root / "bin" / "arducopter";
  if (!executable(binary)) {
    return missing("COVER_ARDUPILOT_SITL=" + dir + " holds no executable bin/arducopter");
  }
  // A staged copy keeps the defaults beside the binary; ArduPilot's tree has them two
  // levels above its build directory.
  const std::vector<fs::path> defaults{
      root / "params" / "copter.parm",
      root / ".." / ".." / "Tools" / "autotest" / "default_params" / "copter.parm"};
  for (const fs::path& parm : defaults) {
    if (fs::is_regular_file(parm)) return {FirmwareBuild{binary, fs::canonical(parm)}, ""};
  }
  return missing("COVER_ARDUPILOT_SITL=" + dir +
                 " has no SITL defaults file copter.parm (looked in params/ and in "
                 "../../Tools/autotest/default_params/)");
}

bool firmware_required() {
  return env("COVER_REQUIRE_FIRMWARE") == "1";
}

}  // namespace cover::firmware
