#include "cover/wire/enums.hpp"

#include <array>
#include <utility>

#include "enum_table.hpp"

namespace cover::wire {
namespace {

using detail::lib_to_wire;
using detail::wire_to_lib;
using mission::Failsafe;
using mission::MissionState;
using model::Stage;

constexpr std::array<std::pair<Stage, msg::Stage>, 3> kStages{{
    {Stage::Initial, msg::Stage::STAGE_INITIAL},
    {Stage::Transition, msg::Stage::STAGE_TRANSITION},
    {Stage::Final, msg::Stage::STAGE_FINAL},
}};

constexpr std::array<std::pair<MissionState, msg::TaskState>, 5> kTaskStates{{
    {MissionState::NotStarted, msg::TaskState::TASK_PENDING},
    {MissionState::Running, msg::TaskState::TASK_RUNNING},
    {MissionState::Complete, msg::TaskState::TASK_SUCCEEDED},
    {MissionState::Failed, msg::TaskState::TASK_FAILED},
    {MissionState::Aborted, msg::TaskState::TASK_CANCELLED},
}};

constexpr std::array<std::pair<Failsafe, msg::FailsafeState>, 11> kFailsafes{{
    {Failsafe::None, msg::FailsafeState::FAILSAFE_NONE},
    {Failsafe::WaitingForInputs, msg::FailsafeState::FAILSAFE_WAITING_FOR_INPUTS},
    {Failsafe::EmergencyHover, msg::FailsafeState::FAILSAFE_EMERGENCY_HOVER},
    {Failsafe::SolverError, msg::FailsafeState::FAILSAFE_SOLVER_ERROR},
    {Failsafe::MissionFailed, msg::FailsafeState::FAILSAFE_MISSION_FAILED},
    {Failsafe::Landed, msg::FailsafeState::FAILSAFE_LANDED},
    {Failsafe::Aborted, msg::FailsafeState::FAILSAFE_ABORTED},
    {Failsafe::ImuHold, msg::FailsafeState::FAILSAFE_IMU_HOLD},
    {Failsafe::EmergencyLanding, msg::FailsafeState::FAILSAFE_EMERGENCY_LANDING},
    {Failsafe::EmergencyLanded, msg::FailsafeState::FAILSAFE_EMERGENCY_LANDED},
    {Failsafe::AutopilotControl, msg::FailsafeState::FAILSAFE_AUTOPILOT_CONTROL},
}};

constexpr std::array<std::pair<mission::FinalAction, msg::FinalAction>, 3> kFinalActions{{
    {mission::FinalAction::None, msg::FinalAction::FINAL_ACTION_NONE},
    {mission::FinalAction::Land, msg::FinalAction::FINAL_ACTION_LAND},
    {mission::FinalAction::Deliver, msg::FinalAction::FINAL_ACTION_DELIVER},
}};

constexpr std::array<std::pair<model::SpeedSource, msg::SpeedSource>, 3> kSpeedSources{{
    {model::SpeedSource::None, msg::SpeedSource::SPEED_SOURCE_NONE},
    {model::SpeedSource::WheelOdometry, msg::SpeedSource::SPEED_SOURCE_WHEEL_ODOMETRY},
    {model::SpeedSource::Imu, msg::SpeedSource::SPEED_SOURCE_IMU},
}};

}  // namespace

msg::Stage to_msg(Stage stage, MissionState state) {
  if (state == MissionState::NotStarted) return msg::Stage::STAGE_IDLE;
  return lib_to_wire(kStages, stage, msg::Stage::STAGE_IDLE);
}
std::optional<Stage> from_msg(msg::Stage stage) {
  return wire_to_lib(kStages, stage);
}

msg::TaskState to_msg(MissionState state) {
  return lib_to_wire(kTaskStates, state, msg::TaskState::TASK_FAILED);
}
std::optional<MissionState> from_msg(msg::TaskState state) {
  return wire_to_lib(kTaskStates, state);
}

msg::FailsafeState to_msg(Failsafe failsafe) {
  return lib_to_wire(kFailsafes, failsafe, msg::FailsafeState::FAILSAFE_SOLVER_ERROR);
}
std::optional<Failsafe> from_msg(msg::FailsafeState failsafe) {
  return wire_to_lib(kFailsafes, failsafe);
}

msg::FinalAction to_msg(mission::FinalAction action) {
  return lib_to_wire(kFinalActions, action, msg::FinalAction::FINAL_ACTION_NONE);
}
std::optional<mission::FinalAction> from_msg(msg::FinalAction action) {
  return wire_to_lib(kFinalActions, action);
}

msg::SpeedSource to_msg(model::SpeedSource source) {
  return lib_to_wire(kSpeedSources, source, msg::SpeedSource::SPEED_SOURCE_NONE);
}
std::optional<model::SpeedSource> from_msg(msg::SpeedSource source) {
  return wire_to_lib(kSpeedSources, source);
}

}  // namespace cover::wire
