#include "cover/mission/failsafe.hpp"
#include "cover/mission/final_action.hpp"
#include "cover/mission/mission_state.hpp"

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

}  // namespace cover::mission
