// Every wire <-> library mapping, field by field: a swapped, dropped or truncated field or
// an enum value mapped to its neighbour fails here.
#include <gtest/gtest.h>

#include <cmath>

#include "cover/config/config_error.hpp"
#include "cover/mission/task_file.hpp"
#include "cover/wire/control.hpp"
#include "cover/wire/eigen.hpp"
#include "cover/wire/enums.hpp"
#include "cover/wire/fc_state.hpp"
#include "cover/wire/reference.hpp"
#include "cover/wire/sensors.hpp"
#include "cover/wire/solve_status.hpp"
#include "cover/wire/task.hpp"
#include "cover/wire/task_status.hpp"
#include "cover/wire/ugv_imu_measurement.hpp"

namespace {

using Eigen::Vector3d;
namespace msg = cover::msg;
namespace wire = cover::wire;
namespace mission = cover::mission;

void expect_vec(const msg::Vector3& m, const Vector3d& v) {
  EXPECT_EQ(m.x, v.x());
  EXPECT_EQ(m.y, v.y());
  EXPECT_EQ(m.z, v.z());
}

TEST(Wire, StampsRoundToTheNearestNanosecond) {
  EXPECT_EQ(wire::to_stamp_ns(0.01), 10'000'000);
  EXPECT_EQ(wire::to_stamp_ns(12.345), 12'345'000'000);
  EXPECT_EQ(wire::to_stamp_ns(std::nan("")), 0);
  // A library time survives the wire and back to within a nanosecond's rounding.
  for (double t : {0.0, 0.005, 1.23, 59.99, 1.7e9}) {
    EXPECT_NEAR(wire::to_seconds(wire::to_stamp_ns(t)), t, 1e-9 * std::max(1.0, t * 1e-9));
  }
}

TEST(Wire, RelativeStateFieldByField) {
  cover::model::RelativeState s;
  s.stamp_s = 3.25;
  s.position_m = {1.5, -2.25, 0.75};
  s.velocity_m_s = {0.125, 0.5, -0.0625};
  s.attitude = Eigen::Quaterniond(0.9, 0.1, -0.3, 0.2).normalized();
  const msg::RelativeState m = wire::to_msg(s, 3, 5, 0.002);
  EXPECT_EQ(m.uav_id, 3u);
  EXPECT_EQ(m.ugv_id, 5u);
  EXPECT_EQ(m.stamp_ns, 3'250'000'000);
  expect_vec(m.position_m, s.position_m);
  expect_vec(m.velocity_m_s, s.velocity_m_s);
  EXPECT_EQ(m.attitude.w, s.attitude.w());
  EXPECT_EQ(m.attitude.x, s.attitude.x());
  EXPECT_EQ(m.attitude.y, s.attitude.y());
  EXPECT_EQ(m.attitude.z, s.attitude.z());
  EXPECT_TRUE(m.valid);
  EXPECT_EQ(m.position_std_m, 0.002);
  const auto back = wire::from_msg(m);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->stamp_s, 3.25);
  EXPECT_EQ(back->position_m, s.position_m);
  EXPECT_EQ(back->velocity_m_s, s.velocity_m_s);
  EXPECT_EQ(back->attitude.coeffs(), s.attitude.coeffs());
  msg::RelativeState lost = m;
  lost.valid = false;
  EXPECT_FALSE(wire::from_msg(lost));
}

TEST(Wire, UgvImuFieldByField) {
  cover::ugv::FilteredImu imu;
  imu.stamp_s = 1.005;
  imu.specific_force_m_s2 = {0.25, -0.5, 9.75};
  imu.angular_velocity_rad_s = {0.01, -0.02, 0.3};
  imu.angular_acceleration_rad_s2 = {0.0, 0.5, -0.125};
  cover::ugv::SpeedEstimate speed;
  speed.speed_m_s = -0.625;
  speed.source = cover::model::SpeedSource::Imu;
  const msg::UgvImu m = wire::to_msg(imu, speed, 2, 77);
  EXPECT_EQ(m.ugv_id, 2u);
  EXPECT_EQ(m.seq, 77u);
  EXPECT_EQ(m.stamp_ns, 1'005'000'000);
  expect_vec(m.specific_force_m_s2, imu.specific_force_m_s2);
  expect_vec(m.angular_velocity_rad_s, imu.angular_velocity_rad_s);
  expect_vec(m.angular_acceleration_rad_s2, imu.angular_acceleration_rad_s2);
  EXPECT_EQ(m.speed_m_s, -0.625);
  EXPECT_EQ(m.speed_source, msg::SpeedSource::SPEED_SOURCE_IMU);
  const mission::UgvImuMeasurement back = wire::from_msg(m);
  EXPECT_DOUBLE_EQ(back.stamp_s, imu.stamp_s);
  EXPECT_EQ(back.motion.specific_force_m_s2, imu.specific_force_m_s2);
  EXPECT_EQ(back.motion.angular_velocity_rad_s, imu.angular_velocity_rad_s);
  EXPECT_EQ(back.motion.angular_acceleration_rad_s2, imu.angular_acceleration_rad_s2);
  EXPECT_EQ(back.motion.speed_m_s, -0.625);  // reversing passes as is
  EXPECT_EQ(back.motion.speed_source, cover::model::SpeedSource::Imu);
  EXPECT_TRUE(back.motion.speed_valid());

  speed.source = cover::model::SpeedSource::WheelOdometry;
  speed.speed_m_s = 0.75;
  const mission::UgvImuMeasurement wheels = wire::from_msg(wire::to_msg(imu, speed, 2, 78));
  EXPECT_EQ(wheels.motion.speed_source, cover::model::SpeedSource::WheelOdometry);
  EXPECT_EQ(wheels.motion.speed_m_s, 0.75);
}

TEST(Wire, UgvImuHostileSpeedReadsAsNoEstimate) {
  msg::UgvImu m = wire::to_msg(cover::ugv::FilteredImu{}, cover::ugv::SpeedEstimate{}, 0, 1);
  EXPECT_EQ(m.speed_source, msg::SpeedSource::SPEED_SOURCE_NONE);
  EXPECT_FALSE(wire::from_msg(m).motion.speed_valid());
  for (double bad : {std::nan(""), HUGE_VAL, -HUGE_VAL}) {
    m.speed_m_s = bad;
    m.speed_source = msg::SpeedSource::SPEED_SOURCE_WHEEL_ODOMETRY;
    const mission::UgvImuMeasurement back = wire::from_msg(m);
    EXPECT_EQ(back.motion.speed_source, cover::model::SpeedSource::None);
    EXPECT_TRUE(std::isfinite(back.motion.speed_m_s));
  }
  m.speed_m_s = 0.5;
  m.speed_source = static_cast<msg::SpeedSource>(99);  // a foreign writer's value
  EXPECT_EQ(wire::from_msg(m).motion.speed_source, cover::model::SpeedSource::None);
  EXPECT_FALSE(wire::from_msg(m).motion.speed_valid());
}

TEST(Wire, CommandFieldByField) {
  mission::ControlCommand c;
  c.thrust_m_s2 = 10.5;
  c.body_rate_rad_s = {0.1, -0.2, 0.3};
  c.armed = true;
  c.release_payload = true;
  c.handover = true;
  const msg::UavCommand m = wire::to_msg(c, 1, 2.0, 1.99, 42);
  EXPECT_EQ(m.uav_id, 1u);
  EXPECT_EQ(m.stamp_ns, 2'000'000'000);
  EXPECT_EQ(m.measurement_stamp_ns, 1'990'000'000);
  EXPECT_EQ(m.seq, 42u);
  EXPECT_EQ(m.thrust_m_s2, 10.5);
  expect_vec(m.body_rates_rad_s, c.body_rate_rad_s);
  const mission::ControlCommand back = wire::from_msg(m);
  EXPECT_EQ(back.thrust_m_s2, c.thrust_m_s2);
  EXPECT_EQ(back.body_rate_rad_s, c.body_rate_rad_s);
  EXPECT_TRUE(back.armed);
  EXPECT_TRUE(back.release_payload);
  EXPECT_TRUE(m.handover);
  EXPECT_TRUE(back.handover);
}

TEST(Wire, TraceCarriesWhatTheRecorderReads) {
  mission::ControllerStatus s;
  s.stage.state = mission::MissionState::Running;
  s.stage.stage = cover::model::Stage::Transition;
  s.stage.process_index = 2;
  s.stage.reference_ugv = 3;
  s.failsafe = mission::Failsafe::EmergencyHover;
  s.solve_status = cover::sampc::SolveStatus::QpNotConverged;
  s.solve_us = 61.5;
  s.planned = true;
  s.plan_ms = 0.75;
  s.reference_position_m = {1.0, 2.0, 3.0};
  const msg::ControlTrace t = wire::to_trace(s, 4, 5.5);
  EXPECT_EQ(t.uav_id, 4u);
  EXPECT_EQ(t.stamp_ns, 5'500'000'000);
  EXPECT_EQ(t.stage, msg::Stage::STAGE_TRANSITION);
  const mission::ControllerStatus back = wire::from_msg(t);
  EXPECT_EQ(back.stage.state, s.stage.state);
  EXPECT_EQ(back.stage.stage, s.stage.stage);
  EXPECT_EQ(back.stage.process_index, s.stage.process_index);
  EXPECT_EQ(back.stage.reference_ugv, s.stage.reference_ugv);
  EXPECT_EQ(back.failsafe, s.failsafe);
  EXPECT_EQ(back.solve_status, s.solve_status);
  EXPECT_EQ(back.solve_us, s.solve_us);
  EXPECT_EQ(back.planned, s.planned);
  EXPECT_EQ(back.plan_ms, s.plan_ms);
  EXPECT_EQ(back.reference_position_m, s.reference_position_m);
  // A foreign writer's out-of-range enum reads as the safe side.
  msg::ControlTrace bad = t;
  bad.task_state = static_cast<msg::TaskState>(99);
  bad.failsafe = static_cast<msg::FailsafeState>(99);
  EXPECT_EQ(wire::from_msg(bad).stage.state, mission::MissionState::Failed);
  EXPECT_EQ(wire::from_msg(bad).failsafe, mission::Failsafe::SolverError);
}

TEST(Wire, StatusCarriesTheLargestClockOffsetAndItsPeer) {
  mission::ControllerOutput output;
  wire::UavStatusInputs in;
  in.uav_id = 2;
  in.output = &output;
  msg::UavStatus m = wire::to_status(in);
  EXPECT_EQ(m.max_clock_offset_ms, 0.0);
  EXPECT_EQ(m.max_offset_peer, "");  // none measured yet
  in.max_clock_offset_ms = -52.25;
  in.max_offset_peer = "ugv1-pi/cover-ugv-agent-1";
  m = wire::to_status(in);
  EXPECT_EQ(m.max_clock_offset_ms, -52.25);
  EXPECT_EQ(m.max_offset_peer, "ugv1-pi/cover-ugv-agent-1");
  in.max_clock_offset_ms = std::nan("");
  EXPECT_EQ(wire::to_status(in).max_clock_offset_ms, 0.0);
}

TEST(Wire, TaskFieldByField) {
  mission::Task task;
  task.task_id = "deliver-7";
  task.uav_id = 2;
  mission::TransitionProcess p;
  p.from_ugv = 1;
  p.to_ugv = 3;
  p.initial_point_m = {0.1, 0.2, 1.1};
  p.transition_point_m = {0.3, 0.4, 1.2};
  p.final_point_m = {0.5, 0.6, 0.3};
  p.final_action = mission::FinalAction::Deliver;
  p.vmax_m_s = 1.25;
  p.amax_m_s2 = 2.5;
  task.processes = {p, p};
  task.processes[1].final_action = mission::FinalAction::Land;
  task.processes[1].method = "intercept";
  const msg::TransitionTask m = wire::to_msg(task, 1.0);
  EXPECT_EQ(m.processes[0].method, "");
  EXPECT_EQ(m.processes[1].method, "intercept");
  ASSERT_EQ(m.processes.size(), 2u);
  EXPECT_EQ(m.task_id, "deliver-7");
  EXPECT_EQ(m.uav_id, 2u);
  EXPECT_EQ(m.processes[0].final_action, msg::FinalAction::FINAL_ACTION_DELIVER);
  EXPECT_EQ(m.processes[1].final_action, msg::FinalAction::FINAL_ACTION_LAND);
  const mission::Task back = wire::from_msg(m);
  EXPECT_EQ(back.task_id, task.task_id);
  EXPECT_EQ(back.uav_id, task.uav_id);
  ASSERT_EQ(back.processes.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const auto& a = back.processes[i];
    const auto& b = task.processes[i];
    EXPECT_EQ(a.from_ugv, b.from_ugv);
    EXPECT_EQ(a.to_ugv, b.to_ugv);
    EXPECT_EQ(a.initial_point_m, b.initial_point_m);
    EXPECT_EQ(a.transition_point_m, b.transition_point_m);
    EXPECT_EQ(a.final_point_m, b.final_point_m);
    EXPECT_EQ(a.final_action, b.final_action);
    EXPECT_EQ(a.vmax_m_s, b.vmax_m_s);
    EXPECT_EQ(a.amax_m_s2, b.amax_m_s2);
    EXPECT_EQ(a.method, b.method);
  }
  // Hostile ids and actions do not wrap into valid ones: validation rejects them.
  msg::TransitionTask hostile = m;
  hostile.processes[0].to_ugv = 0xFFFFFFFFu;
  hostile.processes[1].final_action = static_cast<msg::FinalAction>(7);
  const mission::Task parsed = wire::from_msg(hostile);
  EXPECT_EQ(parsed.processes[0].to_ugv, -1);
  EXPECT_FALSE(parsed.processes[1].final_point_m.allFinite());
  EXPECT_THROW(mission::validate_task(parsed, 8), cover::config::ConfigError);
  // An unknown method is passed on as it is, and validation names it.
  msg::TransitionTask unknown_method = m;
  unknown_method.processes[1].final_action = msg::FinalAction::FINAL_ACTION_NONE;
  unknown_method.processes[0].method = "warp";
  try {
    mission::validate_task(wire::from_msg(unknown_method), 8);
    ADD_FAILURE() << "an unknown method was accepted";
  } catch (const cover::config::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("processes[0].method: 'warp'"), std::string::npos)
        << e.what();
  }
}

// Every library value maps to a distinct wire value and back; every wire value either maps
// back to the same library value or, where the library has none, to nullopt.
template <typename Lib, typename Wire>
void expect_bijective(std::initializer_list<Lib> values) {
  std::vector<Wire> seen;
  for (const Lib v : values) {
    const Wire w = wire::to_msg(v);
    EXPECT_EQ(std::count(seen.begin(), seen.end(), w), 0) << msg::to_string(w);
    seen.push_back(w);
    EXPECT_EQ(wire::from_msg(w), v) << msg::to_string(w);
  }
  EXPECT_FALSE(wire::from_msg(static_cast<Wire>(msg::EnumCount<Wire>::value)));
}

TEST(Wire, EnumsMapOneToOne) {
  using cover::sampc::SolveStatus;
  using mission::Failsafe;
  using mission::MissionState;
  expect_bijective<Failsafe, msg::FailsafeState>(
      {Failsafe::None, Failsafe::WaitingForInputs, Failsafe::EmergencyHover, Failsafe::SolverError,
       Failsafe::MissionFailed, Failsafe::Landed, Failsafe::Aborted, Failsafe::ImuHold,
       Failsafe::EmergencyLanding, Failsafe::EmergencyLanded, Failsafe::AutopilotControl});
  EXPECT_EQ(msg::EnumCount<msg::FailsafeState>::value, 11u);  // no wire value left unmapped
  expect_bijective<MissionState, msg::TaskState>({MissionState::NotStarted, MissionState::Running,
                                                  MissionState::Complete, MissionState::Failed,
                                                  MissionState::Aborted});
  EXPECT_FALSE(wire::from_msg(msg::TaskState::TASK_REJECTED));
  expect_bijective<SolveStatus, msg::SolverStatus>(
      {SolveStatus::Ok, SolveStatus::SqpNotConverged, SolveStatus::QpNotConverged,
       SolveStatus::InvalidInput, SolveStatus::NonFiniteSolution});
  EXPECT_FALSE(wire::from_msg(msg::SolverStatus::SOLVER_NOT_RUNNING));
  expect_bijective<mission::FinalAction, msg::FinalAction>(
      {mission::FinalAction::None, mission::FinalAction::Land, mission::FinalAction::Deliver});
  using cover::model::SpeedSource;
  expect_bijective<SpeedSource, msg::SpeedSource>(
      {SpeedSource::None, SpeedSource::WheelOdometry, SpeedSource::Imu});
  EXPECT_EQ(msg::EnumCount<msg::SpeedSource>::value, 3u);  // no wire value left unmapped
  for (const auto stage : {cover::model::Stage::Initial, cover::model::Stage::Transition,
                           cover::model::Stage::Final}) {
    const msg::Stage w = wire::to_msg(stage, MissionState::Running);
    EXPECT_EQ(wire::from_msg(w), stage);
    EXPECT_EQ(wire::to_msg(stage, MissionState::NotStarted), msg::Stage::STAGE_IDLE);
  }
  EXPECT_FALSE(wire::from_msg(msg::Stage::STAGE_IDLE));
}

TEST(Wire, ProgressCountsStagesOverTheTask) {
  mission::StageDecision d;
  d.state = mission::MissionState::Running;
  d.process_index = 1;
  d.stage = cover::model::Stage::Transition;
  EXPECT_DOUBLE_EQ(wire::task_progress(d, 2), 4.0 / 6.0);
  d.state = mission::MissionState::Complete;
  EXPECT_DOUBLE_EQ(wire::task_progress(d, 2), 1.0);
}

}  // namespace

namespace {

TEST(Wire, ReferenceSamplesTheWholeStage) {
  cover::planner::TrajectoryPiece piece;
  piece.duration_s = 2.0;
  piece.coefficients(0, 0) = 1.0;  // x starts at 1 ...
  piece.coefficients(1, 0) = 0.5;  // ... and moves at 0.5 m/s
  const cover::planner::Trajectory trajectory({piece});
  const msg::ReferenceTrajectory m =
      wire::to_reference(trajectory, 2, 3.0, 1, cover::model::Stage::Final, 0.1);
  EXPECT_EQ(m.uav_id, 2u);
  EXPECT_EQ(m.reference_ugv, 1u);
  EXPECT_EQ(m.stage, msg::Stage::STAGE_FINAL);
  EXPECT_EQ(m.stamp_ns, 3'000'000'000);
  ASSERT_EQ(m.positions_m.size(), 21u);
  ASSERT_EQ(m.velocities_m_s.size(), 21u);
  EXPECT_DOUBLE_EQ(m.dt_s, 0.1);
  EXPECT_DOUBLE_EQ(m.positions_m.back().x, 2.0);
  EXPECT_DOUBLE_EQ(m.velocities_m_s.front().x, 0.5);
  // A long stage is sampled coarser, never cut short.
  const msg::ReferenceTrajectory coarse =
      wire::to_reference(trajectory, 2, 3.0, 1, cover::model::Stage::Final, 0.001, 50);
  ASSERT_EQ(coarse.positions_m.size(), 50u);
  EXPECT_DOUBLE_EQ(coarse.positions_m.back().x, 2.0);
}

}  // namespace

TEST(Wire, FcNotReadyReasonNamesWhatTheAutopilotLacks) {
  msg::FcState s;
  s.link_ok = true;
  s.armed = true;
  s.mode = msg::FcMode::FC_MODE_OFFBOARD;
  s.offboard_ready = true;
  EXPECT_FALSE(wire::fc_not_ready_reason(s));
  s.armed = false;
  s.auto_disarm_s = -1.0;
  EXPECT_EQ(*wire::fc_not_ready_reason(s), "autopilot disarmed (arm it: cover fc arm 0)");
  s.auto_disarm_s = 11.0;  // PX4: COM_DISARM_PRFLT 10 s + 1 s spool-up
  EXPECT_EQ(*wire::fc_not_ready_reason(s),
            "autopilot disarmed (arm it: cover fc arm 0; it disarms by itself 11 s after arming "
            "unless the UAV takes off)");
  s.armed = true;
  s.flight_blocker = "autopilot parameter ATC_ANGLE_BOOST is 1, COVER needs 0: twice";
  EXPECT_EQ(*wire::fc_not_ready_reason(s), s.flight_blocker);  // before the mode: it holds all
  s.flight_blocker.clear();
  s.mode = msg::FcMode::FC_MODE_MANUAL;
  s.mode_name = "POSCTL";
  EXPECT_EQ(*wire::fc_not_ready_reason(s), "autopilot not in its offboard mode (mode POSCTL)");
  s.mode_name.clear();
  EXPECT_NE(wire::fc_not_ready_reason(s)->find("FC_MODE_MANUAL"), std::string::npos);
  s.link_ok = false;  // the link first: nothing else it says is current
  EXPECT_EQ(*wire::fc_not_ready_reason(s), "flight-controller link lost (no autopilot HEARTBEAT)");
  s = msg::FcState{};
  s.link_ok = true;
  s.armed = true;
  s.mode = msg::FcMode::FC_MODE_OFFBOARD;  // the bridge's own verdict counts too
  EXPECT_EQ(*wire::fc_not_ready_reason(s), "autopilot not ready for offboard flight");
}
