#pragma once
// The firmware tests' scenarios, each against a fresh real firmware instance, written once
// for both autopilots (firmware_profile.hpp says how they differ). Each uses gtest's
// assertions; px4_sih_test.cpp and arducopter_test.cpp run them.
#include "cover/firmware/firmware_build.hpp"
#include "firmware_profile.hpp"

namespace cover::firmware::test {

// The bridge finds the firmware (its system id), asks for the streams it reads and gets
// them at the asked rates, reads the parameters COVER depends on as the firmware holds them
// (`cover fc check`), and the operator's offboard, arm, disarm and land are answered by the
// firmware (never an arm by the bridge itself).
void link_streams_parameters_and_operator_commands(const FirmwareProfile& profile,
                                                   const FirmwareBuild& build);

// Parameters that make COVER's flight wrong or unsafe are named by `cover fc check` (exit 1)
// and the blocking ones hold COVER's tasks (flight_blocker).
void wrong_parameters_are_named_and_block_flight(const FirmwareProfile& profile,
                                                 const FirmwareBuild& build);

// A flight from COVER's commands: take-off, the bridge's hover-thrust estimate learns the
// firmware's own hover thrust, a 10 s hover on thrust g and zero rates holds the vertical
// speed, a body-rate step is tracked, and when the agent falls silent the bridge has the
// firmware land within 150 ms of its last command.
void hover_rate_step_and_agent_silent_land(const FirmwareProfile& profile,
                                           const FirmwareBuild& build);

// The bridge killed in flight (SIGKILL): the firmware's own offboard-loss failsafe takes
// the UAV after its parameter's delay (PX4 COM_OF_LOSS_T: land; ArduCopter GUID_TIMEOUT:
// level and hold the altitude).
void firmware_failsafe_when_the_bridge_dies(const FirmwareProfile& profile,
                                            const FirmwareBuild& build);

// A mode change the bridge did not ask for (a ground station's, as a safety pilot's RC
// switch): the bridge reports it, offboard_ready goes false, the bridge does not take the
// UAV back; the operator's land is accepted and a disarm in flight refused by the firmware.
void pilot_mode_change_is_reported_and_not_taken_back(const FirmwareProfile& profile,
                                                      const FirmwareBuild& build);

}  // namespace cover::firmware::test
