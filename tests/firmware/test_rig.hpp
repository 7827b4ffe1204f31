#pragma once
// The firmware tests' FirmwareRig: the bridge and the CLI this build made, the test's
// scratch folder, deadlines stretched by COVER_TEST_TIME_SCALE.
#include "cover/firmware/firmware_rig.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/test/time_scale.hpp"

namespace cover::firmware::test {

inline RigSetup test_rig_setup() {
  RigSetup setup;
  setup.fc_bridge = COVER_FC_BRIDGE;
  setup.cli = COVER_CLI;
  setup.workdir = cover::test::scratch_dir();
  setup.deadline_scale = cover::test::time_scale();
  return setup;
}

class FirmwareRig : public firmware::FirmwareRig {
 public:
  FirmwareRig(const FirmwareProfile& profile, const FirmwareBuild& build,
              const FirmwareParams& params, double bridge_hover_thrust = 0.0)
      : firmware::FirmwareRig(test_rig_setup(), profile, build, params, bridge_hover_thrust) {}
};

}  // namespace cover::firmware::test
