#include "cover/wire/control.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cover/wire/eigen.hpp"
#include "cover/wire/enums.hpp"
#include "cover/wire/solve_status.hpp"

namespace cover::wire {

msg::UavCommand to_msg(const mission::ControlCommand& command, std::uint32_t uav_id, double stamp_s,
                       double measurement_stamp_s, std::uint32_t seq) {
  msg::UavCommand m;
  m.uav_id = uav_id;
  m.stamp_ns = to_stamp_ns(stamp_s);
  m.seq = seq;
  m.thrust_m_s2 = command.thrust_m_s2;
  m.body_rates_rad_s = to_msg(command.body_rate_rad_s);
  m.armed = command.armed;
  m.release_payload = command.release_payload;
  m.handover = command.handover;
  m.measurement_stamp_ns = to_stamp_ns(measurement_stamp_s);
  return m;
}

mission::ControlCommand from_msg(const msg::UavCommand& m) {
  mission::ControlCommand command;
  command.thrust_m_s2 = m.thrust_m_s2;
  command.body_rate_rad_s = to_eigen(m.body_rates_rad_s);
  command.armed = m.armed;
  command.release_payload = m.release_payload;
  command.handover = m.handover;
  return command;
}

msg::ControlTrace to_trace(const mission::ControllerStatus& status, std::uint32_t uav_id,
                           double stamp_s) {
  msg::ControlTrace t;
  t.uav_id = uav_id;
  t.stamp_ns = to_stamp_ns(stamp_s);
  t.task_state = to_msg(status.stage.state);
  t.stage = to_msg(status.stage.stage, status.stage.state);
  t.process_index = static_cast<std::uint32_t>(status.stage.process_index);
  t.reference_ugv = static_cast<std::uint32_t>(status.stage.reference_ugv);
  t.failsafe = to_msg(status.failsafe);
  t.solver_status = to_msg(status.solve_status);
  t.solve_time_us = status.solve_us;
  t.planned = status.planned;
  t.plan_time_ms = status.plan_ms;
  t.reference_position_m = to_msg(status.reference_position_m);
  t.command_time_us = status.command_us;
  return t;
}

mission::ControllerStatus from_msg(const msg::ControlTrace& t) {
  mission::ControllerStatus status;
  status.stage.state = from_msg(t.task_state).value_or(mission::MissionState::Failed);
  status.stage.stage = from_msg(t.stage).value_or(model::Stage::Initial);
  status.stage.process_index = t.process_index;
  status.stage.reference_ugv = static_cast<int>(t.reference_ugv);
  status.failsafe = from_msg(t.failsafe).value_or(mission::Failsafe::SolverError);
  status.solve_status = from_msg(t.solver_status).value_or(sampc::SolveStatus::NonFiniteSolution);
  status.solve_us = t.solve_time_us;
  status.planned = t.planned;
  status.plan_ms = t.plan_time_ms;
  status.reference_position_m = to_eigen(t.reference_position_m);
  status.command_us = t.command_time_us;
  return status;
}

msg::UavStatus to_status(const UavStatusInputs& in) {
  const mission::ControllerStatus& status = in.output->status;
  msg::UavStatus m;
  m.uav_id = in.uav_id;
  m.stamp_ns = to_stamp_ns(in.stamp_s);
  m.task_id = in.task_id;
  m.task_state = to_msg(in.state);
  m.stage = to_msg(status.stage.stage, in.state);
  m.process_index = static_cast<std::uint32_t>(status.stage.process_index);
  m.process_count = in.process_count;
  m.reference_ugv = static_cast<std::uint32_t>(status.stage.reference_ugv);
  m.solver_status =
      status.solve_us > 0.0 ? to_msg(status.solve_status) : msg::SolverStatus::SOLVER_NOT_RUNNING;
  m.solver_iterations = status.solve_us > 0.0 ? 1 : 0;  // real-time iteration: one SQP step
  m.solve_time_us = status.solve_us;
  m.failsafe = to_msg(status.failsafe);
  m.armed = in.output->command.armed;
  m.payload_attached = in.payload_attached;
  m.distance_to_stage_point_m = (in.position_m - status.stage.target_point_m).norm();
  m.speed_m_s = in.velocity_m_s.norm();
  m.rejected_samples = static_cast<std::uint32_t>(
      std::min<std::uint64_t>(in.rejected_samples, std::numeric_limits<std::uint32_t>::max()));
  m.max_clock_offset_ms = std::isfinite(in.max_clock_offset_ms) ? in.max_clock_offset_ms : 0.0;
  m.max_offset_peer = in.max_offset_peer;
  return m;
}

}  // namespace cover::wire
