#pragma once
// The firmware tests' scenarios, each against a fresh real firmware instance, written once
// for both autopilots (firmware_profile.hpp says how they differ). Each uses gtest's
// assertions; px4_sih_test.cpp and arducopter_test.cpp run them.
#include "cover/firmware/firmware_build.hpp"
#include "cover/firmware/firmware_profile.hpp"

namespace cover::firmware::test {

// The bridge finds the firmware (its system id), asks for the streams it reads and gets them
// at the asked rates, and reads the parameters COVER depends on as the firmware holds them
// (`cover fc check`).
void link_streams_and_parameters(const FirmwareProfile& profile, const FirmwareBuild& build);

// Parameters that make COVER's flight wrong or unsafe are named by `cover fc check` (exit 1)
// and a blocking one holds COVER's tasks (flight_blocker).
void wrong_parameters_are_named_and_block_flight(const FirmwareProfile& profile,
                                                 const FirmwareBuild& build);

// One flight from COVER's commands, the firmware's ~40 s start-up paid once (ArduCopter's
// EKF takes that long to use SITL's GPS):
//  - on the ground the operator's `cover fc offboard|arm|disarm|arm 0`, each answered by the
//    firmware, and the bridge never arms by itself;
//  - take-off; the bridge's hover-thrust estimate, started ~10 % off, learns the firmware's
//    hover thrust, and a 10 s hover on thrust g and zero rates holds the vertical speed;
//  - a body-rate step is tracked;
//  - the agent falls silent: the firmware accepts the bridge's land within 150 ms of the
//    agent's last command;
//  - the operator gives the UAV back to COVER (`cover fc offboard 0` in flight);
//  - a mode change the bridge did not ask for (a ground station's; a safety pilot's RC
//    switch takes the same path): reported, offboard_ready false, not taken back; the
//    firmware refuses a disarm in flight and accepts the operator's land;
//  - the operator gives it back again, and the bridge is killed (SIGKILL): the firmware's
//    own offboard-loss failsafe takes the UAV after its parameter's delay (PX4
//    COM_OF_LOSS_T: land; ArduCopter GUID_TIMEOUT: level and hold the altitude).
void flight_from_cover_commands(const FirmwareProfile& profile, const FirmwareBuild& build);

}  // namespace cover::firmware::test
