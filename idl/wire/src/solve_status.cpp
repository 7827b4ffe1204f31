#include "cover/wire/solve_status.hpp"

#include <array>
#include <utility>

#include "enum_table.hpp"

namespace cover::wire {
namespace {

using detail::lib_to_wire;
using detail::wire_to_lib;
using sampc::SolveStatus;

constexpr std::array<std::pair<SolveStatus, msg::SolverStatus>, 5> kSolveStatuses{{
    {SolveStatus::Ok, msg::SolverStatus::SOLVER_OK},
    {SolveStatus::SqpNotConverged, msg::SolverStatus::SOLVER_SQP_NOT_CONVERGED},
    {SolveStatus::QpNotConverged, msg::SolverStatus::SOLVER_QP_NOT_CONVERGED},
    {SolveStatus::InvalidInput, msg::SolverStatus::SOLVER_INVALID_INPUT},
    {SolveStatus::NonFiniteSolution, msg::SolverStatus::SOLVER_NON_FINITE},
}};

}  // namespace

msg::SolverStatus to_msg(SolveStatus status) {
  return lib_to_wire(kSolveStatuses, status, msg::SolverStatus::SOLVER_NON_FINITE);
}
std::optional<SolveStatus> from_msg(msg::SolverStatus status) {
  return wire_to_lib(kSolveStatuses, status);
}

}  // namespace cover::wire
