#pragma once
// Where a real firmware's SITL build is, found from the environment (docs/flight-controller.md,
// "The real firmware in the loop"):
//   COVER_PX4_SITL        a PX4 SITL build directory, as PX4's `make px4_sitl` leaves it in
//                         build/px4_sitl_default: bin/px4 and etc/ (the ROMFS it boots from)
//   COVER_ARDUPILOT_SITL  an ArduCopter SITL build directory, as ArduPilot's
//                         `./waf configure --board sitl && ./waf copter` leaves it in build/sitl:
//                         bin/arducopter, and SITL's defaults file copter.parm in params/ or,
//                         in ArduPilot's own tree, ../../Tools/autotest/default_params/
//   COVER_REQUIRE_FIRMWARE=1  a firmware that cannot be found fails a test instead of skipping
//                         it (CI sets it: there the firmware must run)
#include <filesystem>
#include <optional>
#include <string>

namespace cover::firmware {

struct FirmwareBuild {
  std::filesystem::path binary;  // bin/px4 or bin/arducopter
  std::filesystem::path data;    // PX4: etc/; ArduCopter: copter.parm
};

struct FirmwareLookup {
  std::optional<FirmwareBuild> build;
  std::string missing;  // when there is none: why, and how to point at a build
};

FirmwareLookup find_px4_sitl();
FirmwareLookup find_arducopter_sitl();

bool firmware_required();

}  // namespace cover::firmware
