#pragma once

#include <cstdint>

namespace cover::sampc {

// Outcome of one SAMPC call. Every status comes with a finite command within the bounds:
// the error statuses (see is_error) come with the hover command.
enum class SolveStatus : std::uint8_t {
  Ok = 0,             // QP solved; for RTI one SQP step, otherwise converged
  SqpNotConverged,    // iterate-to-convergence mode hit max_sqp_iterations (command usable)
  QpNotConverged,     // the active-set QP hit max_qp_iterations; command clamped (usable)
  InvalidInput,       // non-finite or absurd measurement / UGV motion / reference: hover
  NonFiniteSolution,  // the solver produced NaN/Inf: hover, warm start discarded
};

inline const char* to_string(SolveStatus status) {
  switch (status) {
    case SolveStatus::Ok:
      return "ok";
    case SolveStatus::SqpNotConverged:
      return "sqp_not_converged";
    case SolveStatus::QpNotConverged:
      return "qp_not_converged";
    case SolveStatus::InvalidInput:
      return "invalid_input";
    case SolveStatus::NonFiniteSolution:
      return "non_finite_solution";
  }
  return "unknown";
}

// True when the command is the hover fallback rather than an optimised input.
inline bool is_error(SolveStatus status) {
  return status == SolveStatus::InvalidInput || status == SolveStatus::NonFiniteSolution;
}

}  // namespace cover::sampc
