// cover-fc-bridge against the real ArduCopter (SITL, its built-in multicopter physics): a fresh one
// per test, found through COVER_ARDUPILOT_SITL (sim/firmware/include/cover/firmware/
// firmware_build.hpp). Without one the tests skip, saying how to point at a build; with
// COVER_REQUIRE_FIRMWARE=1 (CI) they fail instead.
#include <gtest/gtest.h>

#include "scenarios.hpp"

namespace cover::firmware::test {
namespace {

class ArduCopter : public ::testing::Test {
 protected:
  void SetUp() override {
    lookup_ = find_arducopter_sitl();
    if (lookup_.build) return;
    if (firmware_required()) FAIL() << lookup_.missing << " (COVER_REQUIRE_FIRMWARE=1)";
    GTEST_SKIP() << lookup_.missing;
  }
  const FirmwareBuild& build() const { return *lookup_.build; }
  FirmwareLookup lookup_;
};

TEST_F(ArduCopter, LinkStreamsAndParameters) {
  link_streams_and_parameters(arducopter_profile(), build());
}

TEST_F(ArduCopter, WrongParametersAreNamedAndBlockFlight) {
  wrong_parameters_are_named_and_block_flight(arducopter_profile(), build());
}

TEST_F(ArduCopter, FlightFromCoverCommands) {
  flight_from_cover_commands(arducopter_profile(), build());
}

}  // namespace
}  // namespace cover::firmware::test
