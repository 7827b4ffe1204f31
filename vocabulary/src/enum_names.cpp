#include "cover/vocabulary/failsafe.hpp"
#include "cover/vocabulary/failsafe_cause.hpp"
#include "cover/vocabulary/failure_reason.hpp"
#include "cover/vocabulary/final_action.hpp"
#include "cover/vocabulary/mission_state.hpp"

namespace cover::mission {

const char* to_string(FinalAction action) {
  switch (action) {
    case FinalAction::None:
      return "none";
    case FinalAction::Land:
      return "land";
    case FinalAction::Deliver:
      return "deliver";
  }
  return "unknown";
}

const char* to_string(MissionState state) {
  switch (state) {
    case MissionState::NotStarted:
      return "not-started";
    case MissionState::Running:
      return "running";
    case MissionState::Complete:
      return "complete";
    case MissionState::Failed:
      return "failed";
    case MissionState::Aborted:
      return "aborted";
  }
  return "unknown";
}

const char* to_string(Failsafe failsafe) {
  switch (failsafe) {
    case Failsafe::None:
      return "none";
    case Failsafe::WaitingForInputs:
      return "waiting-for-inputs";
    case Failsafe::EmergencyHover:
      return "emergency-hover";
    case Failsafe::SolverError:
      return "solver-error";
    case Failsafe::MissionFailed:
      return "mission-failed";
    case Failsafe::Landed:
      return "landed";
    case Failsafe::Aborted:
      return "aborted";
    case Failsafe::ImuHold:
      return "imu-hold";
    case Failsafe::EmergencyLanding:
      return "emergency-landing";
    case Failsafe::EmergencyLanded:
      return "emergency-landed";
    case Failsafe::AutopilotControl:
      return "autopilot-control";
  }
  return "unknown";
}

const char* to_string(FailureReason reason) {
  switch (reason) {
    case FailureReason::None:
      return "none";
    case FailureReason::StageTimeout:
      return "stage-timeout";
    case FailureReason::InvalidState:
      return "invalid-state";
    case FailureReason::StaleInput:
      return "stale-input";
    case FailureReason::PlanningFailed:
      return "planning-failed";
    case FailureReason::AutopilotControl:
      return "autopilot-control";
  }
  return "unknown";
}

const char* to_string(FailsafeCause cause) {
  switch (cause) {
    case FailsafeCause::None:
      return "none";
    case FailsafeCause::ClockInvalid:
      return "clock-invalid";
    case FailsafeCause::StateMissing:
      return "relative-state-missing";
    case FailsafeCause::StateInvalid:
      return "relative-state-invalid";
    case FailsafeCause::StateStale:
      return "relative-state-stale";
    case FailsafeCause::ImuMissing:
      return "ugv-imu-missing";
    case FailsafeCause::ImuInvalid:
      return "ugv-imu-invalid";
    case FailsafeCause::ImuStale:
      return "ugv-imu-stale";
  }
  return "unknown";
}

}  // namespace cover::mission
