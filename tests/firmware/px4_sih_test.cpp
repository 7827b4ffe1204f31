// cover-fc-bridge against the real PX4 (SITL, its built-in SIH physics): a fresh PX4 per
// test, found through COVER_PX4_SITL (sim/firmware/include/cover/firmware/
// firmware_build.hpp). Without one the tests skip, saying how to point at a build; with
// COVER_REQUIRE_FIRMWARE=1 (CI) they fail instead.
#include <gtest/gtest.h>

#include "scenarios.hpp"

namespace cover::firmware::test {
namespace {

class Px4Sih : public ::testing::Test {
 protected:
  void SetUp() override {
    lookup_ = find_px4_sitl();
    if (lookup_.build) return;
    if (firmware_required()) FAIL() << lookup_.missing << " (COVER_REQUIRE_FIRMWARE=1)";
    GTEST_SKIP() << lookup_.missing;
  }
  const FirmwareBuild& build() const { return *lookup_.build; }
  FirmwareLookup lookup_;
};

TEST_F(Px4Sih, LinkStreamsAndParameters) {
  link_streams_and_parameters(px4_sih_profile(), build());
}

TEST_F(Px4Sih, WrongParametersAreNamedAndBlockFlight) {
  wrong_parameters_are_named_and_block_flight(px4_sih_profile(), build());
}

TEST_F(Px4Sih, FlightFromCoverCommands) {
  flight_from_cover_commands(px4_sih_profile(), build());
}

}  // namespace
}  // namespace cover::firmware::test
