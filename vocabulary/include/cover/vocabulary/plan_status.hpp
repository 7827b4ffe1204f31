#pragma once

namespace cover::planner {

// Outcome of one stage plan. Whatever the status, PlanResult::trajectory is finite and
// can be flown or held; the status says how much to trust it.
enum class PlanStatus {
  Ok,            // optimiser converged (tolerances met, or stopped at rounding precision)
  EarlyStop,     // usable: the optimiser hit its evaluation or time budget first
  InvalidInput,  // NaN/inf or absurd input; trajectory holds the start (or origin)
  Failed,        // optimiser broke down; trajectory is the safe initial guess
};

inline const char* to_string(PlanStatus status) {
  switch (status) {
    case PlanStatus::Ok:
      return "ok";
    case PlanStatus::EarlyStop:
      return "early_stop";
    case PlanStatus::InvalidInput:
      return "invalid_input";
    case PlanStatus::Failed:
      return "failed";
  }
  return "unknown";
}

// True when the trajectory is the optimiser's (converged or not), not a fallback.
inline bool is_usable(PlanStatus status) {
  return status == PlanStatus::Ok || status == PlanStatus::EarlyStop;
}

}  // namespace cover::planner
