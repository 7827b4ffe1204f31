// The simulated autopilots against what real PX4 SITL and ArduCopter SITL did with COVER's
// bridge (docs/autopilots.md, measured on real SITL, docs/autopilots.md "Our simulated autopilots
// and the real firmware"): streams and SET_MESSAGE_INTERVAL, the lockstep closing IMU, who says
// what and when, the parameters and their types, auto-disarm, the estimator's state. Each decoded
// with our codec and, where the bridge reads it, with the bridge's own decoders.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "autopilot_bench.hpp"
#include "cover/fc_bridge/estimator_health.hpp"
#include "cover/mavlink/state_messages.hpp"
#include "cover/sim/fc/px4_event.hpp"

namespace {

using cover::Autopilot;
using cover::sim::fc::AutopilotEvent;
using cover::sim::fc::FlightMode;
using cover::sim::fc::SimFcParams;
using cover::sim::fc::StepClosing;
using cover::sim::fc::test::AutopilotBench;
using cover::sim::fc::test::ground_world;
namespace mav = cover::mavlink;
namespace px4 = cover::mavlink::px4_mode;
namespace copter = cover::mavlink::copter_mode;

double disarmed_at(const cover::sim::fc::SimulatedAutopilot& autopilot) {
  for (const auto& e : autopilot.events()) {
    if (e.kind == AutopilotEvent::Kind::Arming && e.text.rfind("Disarmed", 0) == 0) {
      return e.time_s;
    }
  }
  return -1.0;
}

// --- streams ---------------------------------------------------------------------------

// ArduCopter SITL: HEARTBEAT only; each stream asked with SET_MESSAGE_INTERVAL answered 0
// and delivered at exactly the asked rate; 0 = its default (off), -1 off; a message it has
// no stream of refused 2 DENIED with "No ap_message for mavlink id (230)".
TEST(FirmwareBehaviour, ArduPilotStreamsNothingButHeartbeatUntilAskedThenAtTheAskedRate) {
  AutopilotBench bench(Autopilot::ArduPilot);
  bench.idle(3.0);
  EXPECT_EQ(bench.sent<mav::Heartbeat>().size(), 3u);
  EXPECT_EQ(bench.received().size(), 3u) << "anything but HEARTBEAT before a request";

  EXPECT_EQ(bench.interval(mav::HighresImu::kId, 10000.0F)->result, mav::mav_result::kAccepted);
  EXPECT_EQ(bench.interval(mav::ExtendedSysState::kId, 200000.0F)->result,
            mav::mav_result::kAccepted);
  EXPECT_EQ(bench.interval(mav::EkfStatusReport::kId, 1e6F)->result, mav::mav_result::kAccepted);
  bench.clear();
  bench.idle(2.0);
  EXPECT_EQ(bench.sent<mav::HighresImu>().size(), 200u);
  EXPECT_EQ(bench.sent<mav::ExtendedSysState>().size(), 10u);
  EXPECT_EQ(bench.sent<mav::EkfStatusReport>().size(), 2u);
  EXPECT_TRUE(bench.sent<mav::AttitudeQuaternion>().empty());

  EXPECT_EQ(bench.interval(mav::HighresImu::kId, -1.0F)->result, mav::mav_result::kAccepted);
  EXPECT_EQ(bench.interval(mav::ExtendedSysState::kId, 0.0F)->result, mav::mav_result::kAccepted);
  bench.clear();
  bench.idle(1.0);
  EXPECT_TRUE(bench.sent<mav::HighresImu>().empty());
  EXPECT_TRUE(bench.sent<mav::ExtendedSysState>().empty());  // its default: off
  EXPECT_EQ(bench.sent<mav::EkfStatusReport>().size(), 1u);

  bench.clear();
  EXPECT_EQ(bench.interval(mav::EstimatorStatus::kId, 1e5F)->result, mav::mav_result::kDenied);
  EXPECT_EQ(bench.last_statustext(), "No ap_message for mavlink id (230)");
}

// PX4 SITL: HIGHRES_IMU 49.7 Hz by default, 99.3 asked at 100, back to 49.3 at 0, off at -1;
// an unsupported message 4 FAILED.
TEST(FirmwareBehaviour, Px4StreamRatesChangePerMessage) {
  AutopilotBench bench(Autopilot::Px4);
  bench.idle(1.0);
  EXPECT_EQ(bench.sent<mav::HighresImu>().size(), 50u);
  EXPECT_EQ(bench.interval(mav::HighresImu::kId, 10000.0F)->result, mav::mav_result::kAccepted);
  EXPECT_EQ(bench.interval(mav::SysStatus::kId, 500000.0F)->result, mav::mav_result::kAccepted);
  bench.clear();
  bench.idle(1.0);
  EXPECT_EQ(bench.sent<mav::HighresImu>().size(), 100u);
  EXPECT_EQ(bench.sent<mav::SysStatus>().size(), 2u);
  EXPECT_EQ(bench.sent<mav::AttitudeQuaternion>().size(), 50u);  // the others unchanged
  EXPECT_EQ(bench.interval(mav::HighresImu::kId, 0.0F)->result, mav::mav_result::kAccepted);
  EXPECT_EQ(bench.interval(mav::AttitudeTarget::kId, -1.0F)->result, mav::mav_result::kAccepted);
  bench.clear();
  bench.idle(1.0);
  EXPECT_EQ(bench.sent<mav::HighresImu>().size(), 50u);
  EXPECT_TRUE(bench.sent<mav::AttitudeTarget>().empty());
  EXPECT_EQ(bench.interval(mav::EkfStatusReport::kId, 1e6F)->result, mav::mav_result::kFailed);
  EXPECT_EQ(bench.interval(mav::HighresImu::kId, -7.0F)->result, mav::mav_result::kFailed);
  EXPECT_DOUBLE_EQ(bench.autopilot().stream_rate_hz(mav::HighresImu::kId), 50.0);
}

// LOCAL_POSITION_NED (the vertical velocity that aids the bridge's hover-thrust estimate):
// both send it when asked (real PX4 SIH and ArduCopter SITL accepted 50 Hz with ACK 0 and
// sent it, FlightFromCoverCommands); neither of ours sends it unasked. A vehicle resting on
// the ground: position and velocity zero.
TEST(FirmwareBehaviour, BothSendLocalPositionNedWhenAsked) {
  for (const auto profile : {Autopilot::Px4, Autopilot::ArduPilot}) {
    AutopilotBench bench(profile);
    bench.idle(1.0);
    EXPECT_TRUE(bench.sent<mav::LocalPositionNed>().empty());
    EXPECT_EQ(bench.interval(mav::LocalPositionNed::kId, 20000.0F)->result,
              mav::mav_result::kAccepted);
    bench.clear();
    bench.idle(1.0);
    const auto positions = bench.sent<mav::LocalPositionNed>();
    ASSERT_EQ(positions.size(), 50u);
    EXPECT_NEAR(positions.back().vz, 0.0F, 1e-3F);
    EXPECT_NEAR(positions.back().z, 0.0F, 0.5F);
  }
}

// A rate change lands on the new rate's grid of simulated time: a frame both rates would
// send does not move, whenever the request came.
TEST(FirmwareBehaviour, AStreamChangedBetweenGridPointsKeepsItsPhase) {
  AutopilotBench bench(Autopilot::Px4);
  bench.idle(0.13);
  bench.interval(mav::SysStatus::kId, 500000.0F);  // 2 Hz, asked at 0.13 s
  bench.clear();
  std::vector<double> stamps;
  for (int i = 0; i < 150; ++i) {
    const double t = bench.t_s();
    const std::size_t before = bench.sent<mav::SysStatus>().size();
    bench.tick();
    if (bench.sent<mav::SysStatus>().size() > before) stamps.push_back(t);
  }
  ASSERT_EQ(stamps.size(), 3u);
  EXPECT_NEAR(stamps[0], 0.5, 1e-9);
  EXPECT_NEAR(stamps[1], 1.0, 1e-9);
  EXPECT_NEAR(stamps[2], 1.5, 1e-9);
}

// The simulator's own lockstep contract (real firmware has none): every step's frames end
// with a HIGHRES_IMU stamped with the step's time, whatever the stream's rate, even off.
TEST(FirmwareBehaviour, LockstepClosesEveryStepWithAHighresImuWhateverItsRate) {
  for (const auto profile : {Autopilot::Px4, Autopilot::ArduPilot}) {
    AutopilotBench bench(profile, ground_world(), SimFcParams{}, StepClosing::HighresImu);
    for (int i = 0; i < 40; ++i) {
      const double t = bench.t_s();
      bench.clear();
      bench.tick();
      ASSERT_FALSE(bench.received().empty());
      const auto imu = mav::decode<mav::HighresImu>(bench.received().back());
      ASSERT_TRUE(imu) << "step " << i << " not closed by a HIGHRES_IMU";
      EXPECT_EQ(imu->time_usec, static_cast<std::uint64_t>(std::llround(t * 1e6)));
      EXPECT_EQ(bench.sent<mav::HighresImu>().size(), 1u);
    }
  }
  AutopilotBench realtime(Autopilot::ArduPilot);
  realtime.idle(0.5);
  EXPECT_TRUE(realtime.sent<mav::HighresImu>().empty());
}

// --- who says what ---------------------------------------------------------------------

// ArduPilot sends STATUSTEXT only to a link that has received a MAVLink frame.
TEST(FirmwareBehaviour, ArduPilotSpeaksOnlyOnceItsLinkHasHeardAFrame) {
  SimFcParams params;
  params.ardupilot.estimator_align_s = 0.5;
  AutopilotBench silent(Autopilot::ArduPilot, ground_world(), params);
  silent.idle(1.0);
  EXPECT_TRUE(silent.sent<mav::StatusText>().empty());

  AutopilotBench heard(Autopilot::ArduPilot, ground_world(), params);
  heard.companion_heartbeat();
  heard.idle(1.0);
  EXPECT_EQ(heard.last_statustext(), "EKF3 IMU0 tilt alignment complete");
}

// PX4 SITL sent no STATUSTEXT in three runs; each change is an EVENT, in sequence.
TEST(FirmwareBehaviour, Px4ReportsThroughEventsNeverStatustext) {
  AutopilotBench bench(Autopilot::Px4);
  bench.stream(1.0, 0.0F);
  bench.set_mode(px4::kMainOffboard);
  bench.arm();
  bench.stream(1.0, 0.7F);  // takes off
  bench.idle(3.0);          // offboard lost: descends
  EXPECT_TRUE(bench.sent<mav::StatusText>().empty());
  const auto texts = bench.event_texts();
  EXPECT_EQ(texts, (std::vector<std::string>{"Armed by external command", "Takeoff detected",
                                             "Failsafe activated: switching to Descend"}));
  const auto events = bench.sent<mav::Event>();
  for (std::size_t i = 0; i < events.size(); ++i) EXPECT_EQ(events[i].sequence, i);
  EXPECT_NEAR(events[1].event_time_boot_ms, 1030, 20);
}

// The bridge contract's event ids and argument packing, written by the simulator on its own.
TEST(FirmwareBehaviour, Px4EventIdsAndArgumentsAsLibevents) {
  // FNV-1a-32 of "commander_armed_by", low 24 bits, under component 1.
  std::uint32_t hash = 2166136261U;
  for (const char c : std::string("commander_armed_by")) hash = (hash ^ c) * 16777619U;
  EXPECT_EQ(cover::sim::fc::px4_event_id("commander_armed_by"), (1U << 24) | (hash & 0xFFFFFF));
  const mav::Event e = cover::sim::fc::Px4Event("commander_failsafe_enter_generic",
                                                cover::sim::fc::Px4EventLevel::Critical)
                           .arg(std::uint32_t{0x01020304})
                           .arg(std::uint8_t{8})
                           .message(3, 1500);
  EXPECT_EQ(e.arguments[0], 0x04);  // little-endian
  EXPECT_EQ(e.arguments[3], 0x01);
  EXPECT_EQ(e.arguments[4], 8);
  EXPECT_EQ(e.log_levels, (6 << 4) | 2);  // internal info, external critical
  EXPECT_EQ(cover::fc_bridge::describe_px4_event(e).text,
            "Failsafe activated: switching to Descend");
}

// --- parameters ------------------------------------------------------------------------

struct Answer {
  std::string name;
  std::uint8_t type = 0;
  float field = 0.0F;
  std::uint32_t bits = 0;
  std::uint16_t index = 0;
  std::uint16_t count = 0;
};

std::optional<Answer> answer_of(const std::vector<mav::Frame>& frames) {
  for (const auto& f : frames) {
    if (const auto v = mav::decode<mav::ParamValue>(f)) {
      Answer a{mav::param_id_string(v->param_id),
               v->param_type,
               v->param_value,
               0,
               v->param_index,
               v->param_count};
      std::memcpy(&a.bits, &v->param_value, sizeof a.bits);
      return a;
    }
  }
  return std::nullopt;
}

// As PX4 SITL answered: REAL32 floats, INT32 integers with their bytes copied into the
// float (COM_RC_IN_MODE 1 reads 1.4e-45), its own index; an unknown name PARAM_ERROR.
TEST(FirmwareBehaviour, Px4AnswersItsParametersByNameAndIndexWithPx4sTypes) {
  AutopilotBench bench(Autopilot::Px4);
  const struct {
    const char* name;
    std::uint8_t type;
    double value;
  } expected[] = {{"COM_OF_LOSS_T", 9, 1.0},   {"COM_OBL_RC_ACT", 6, 0.0},
                  {"MPC_THR_HOVER", 9, 0.5},   {"COM_DISARM_PRFLT", 9, 10.0},
                  {"COM_DISARM_LAND", 9, 2.0}, {"COM_RC_IN_MODE", 6, 1.0},
                  {"NAV_DLL_ACT", 6, 0.0},     {"MAV_SYS_ID", 6, 3.0}};
  for (const auto& e : expected) {
    const auto a = answer_of(bench.read_parameter(e.name));
    ASSERT_TRUE(a) << e.name;
    EXPECT_EQ(a->name, e.name);
    EXPECT_EQ(a->type, e.type) << e.name;
    EXPECT_EQ(mav::param_value_of(a->field, a->type, mav::ParamEncoding::Bytewise), e.value)
        << e.name;
    EXPECT_NE(a->index, 65535) << e.name;
  }
  EXPECT_EQ(answer_of(bench.read_parameter("COM_RC_IN_MODE"))->bits, 1u);  // bytewise
  const auto by_index = answer_of(bench.read_parameter("", 1));
  ASSERT_TRUE(by_index);
  EXPECT_EQ(by_index->name, "COM_OBL_RC_ACT");
  EXPECT_EQ(by_index->index, 1);
  EXPECT_GE(by_index->count, 7);

  bench.idle(0.05);  // past t = 0, where ALTITUDE and VFR_HUD (10 Hz) are due
  const auto unknown_before = bench.parser_stats().unknown_frames;
  const auto frames = bench.read_parameter("NO_SUCH_PARAM");
  bench.tick();  // a frame after it: the parser counts an unknown frame once another follows
  EXPECT_FALSE(answer_of(frames));
  EXPECT_EQ(bench.parser_stats().unknown_frames, unknown_before + 1);  // PARAM_ERROR (345)
  EXPECT_EQ(bench.parser_stats().errors(), 0u);
}

// As ArduCopter SITL answered: INT8, INT32, REAL32, INT16 values converted into the float,
// param_index 65535 for a request by name; SYSID_THISMAV (before 4.7) and unknown names
// get no answer. Values from config/sim/sim_fc.yaml: a wrong ATC_ANGLE_BOOST is reported.
TEST(FirmwareBehaviour, ArduPilotAnswersItsParametersWithArduPilotsTypes) {
  SimFcParams params;
  params.ardupilot.atc_angle_boost = 1;
  params.ardupilot.disarm_delay_s = 7;
  AutopilotBench bench(Autopilot::ArduPilot, ground_world(), params);
  const struct {
    const char* name;
    std::uint8_t type;
    float value;
  } expected[] = {{"ATC_ANGLE_BOOST", 2, 1.0F}, {"GUID_OPTIONS", 6, 8.0F},
                  {"GUID_TIMEOUT", 9, 3.0F},    {"FS_GCS_ENABLE", 2, 5.0F},
                  {"FS_GCS_TIMEOUT", 9, 5.0F},  {"MAV_GCS_SYSID", 4, 3.0F},  // its own id
                  {"FS_THR_ENABLE", 2, 0.0F},   {"MOT_THST_HOVER", 9, 0.35F},
                  {"DISARM_DELAY", 2, 7.0F},    {"MAV_SYSID", 4, 3.0F}};
  for (const auto& e : expected) {
    const auto a = answer_of(bench.read_parameter(e.name));
    ASSERT_TRUE(a) << e.name;
    EXPECT_EQ(a->type, e.type) << e.name;
    EXPECT_EQ(a->field, e.value) << e.name;  // C cast: the number itself
    EXPECT_EQ(a->index, 65535) << e.name;
  }
  EXPECT_FALSE(answer_of(bench.read_parameter("SYSID_THISMAV")));
  EXPECT_TRUE(bench.read_parameter("NO_SUCH_PARAM").empty());
  EXPECT_EQ(answer_of(bench.read_parameter("", 2))->name, "GUID_TIMEOUT");
  EXPECT_TRUE(bench.read_parameter("", 99).empty());
}

// --- thrust ----------------------------------------------------------------------------

// ATC_ANGLE_BOOST 1: ArduPilot divides the throttle by the cosine of the tilt
// (AC_AttitudeControl_Multi::get_throttle_boosted); 0 flies it unchanged.
TEST(FirmwareBehaviour, ArduPilotAngleBoostDividesTheThrustByTheTiltsCosine) {
  auto world = ground_world();
  world.uav_initial.position_m = Eigen::Vector3d(0.0, 0.0, 5.0);
  for (const int boost : {0, 1}) {
    SimFcParams params;
    params.ardupilot.atc_angle_boost = boost;
    AutopilotBench bench(Autopilot::ArduPilot, world, params);
    bench.set_mode(copter::kGuidedNoGps);
    bench.arm();
    for (int i = 0; i < 30; ++i) {  // roll at 1 rad/s for 0.3 s
      bench.send(bench.setpoint(0.5F, 1.0F));
      bench.tick();
    }
    const auto q = bench.world().state().uav.attitude.eigen();
    const double cos_tilt = (q * Eigen::Vector3d::UnitZ()).z();
    ASSERT_LT(cos_tilt, 0.99);
    bench.send(bench.setpoint(0.5F));
    const double thrust = bench.tick().plant_command.thrust_m_s2;
    const double max = world.uav.max_thrust_m_s2;
    EXPECT_NEAR(thrust, boost == 0 ? 0.5 * max : 0.5 * max / cos_tilt, 1e-6) << boost;
  }
}

// --- auto-disarm -----------------------------------------------------------------------

// PX4 SITL: "Disarmed by preflight inaction" 11 s after arming on the ground
// (COM_DISARM_PRFLT 10 s + 1 s spool-up), in any mode; a take-off ends the count.
TEST(FirmwareBehaviour, Px4DisarmsElevenSecondsAfterArmingUnlessItTookOff) {
  AutopilotBench bench(Autopilot::Px4);
  bench.idle(0.5);
  const double armed_s = bench.t_s();
  ASSERT_EQ(bench.arm()->result, mav::mav_result::kAccepted);
  bench.idle(10.9);
  EXPECT_TRUE(bench.autopilot().armed());
  bench.idle(0.2);
  EXPECT_FALSE(bench.autopilot().armed());
  EXPECT_NEAR(disarmed_at(bench.autopilot()) - armed_s, 11.0, 0.011);
  EXPECT_EQ(bench.event_texts().back(), "Disarmed by preflight inaction");
  EXPECT_EQ(bench.autopilot().mode(), FlightMode::Hold);

  SimFcParams never;
  never.px4.com_disarm_prflt_s = -1.0;
  AutopilotBench kept(Autopilot::Px4, ground_world(), never);
  kept.arm();
  kept.idle(15.0);
  EXPECT_TRUE(kept.autopilot().armed());

  AutopilotBench flying(Autopilot::Px4);
  flying.stream(1.0, 0.0F);
  flying.set_mode(px4::kMainOffboard);
  flying.arm();
  flying.stream(12.0, 0.55F);  // above hover: in the air the whole time
  EXPECT_TRUE(flying.autopilot().armed());
  EXPECT_FALSE(flying.world().state().uav_contact.resting);
}

// ArduCopter SITL: GUIDED_NOGPS, armed without setpoints, on the ground: "Disarming motors"
// 10 s after arming (DISARM_DELAY). A thrust setpoint is not zero throttle.
TEST(FirmwareBehaviour, ArduPilotDisarmsAfterDisarmDelayLandedAtZeroThrottle) {
  AutopilotBench bench(Autopilot::ArduPilot);
  bench.set_mode(copter::kGuidedNoGps);
  const double armed_s = bench.t_s();
  ASSERT_EQ(bench.arm()->result, mav::mav_result::kAccepted);
  bench.idle(9.9);
  EXPECT_TRUE(bench.autopilot().armed());
  bench.idle(0.2);
  EXPECT_FALSE(bench.autopilot().armed());
  EXPECT_NEAR(disarmed_at(bench.autopilot()) - armed_s, 10.0, 0.011);
  EXPECT_EQ(bench.last_statustext(), "Disarming motors");

  AutopilotBench spinning(Autopilot::ArduPilot);
  spinning.set_mode(copter::kGuidedNoGps);
  spinning.arm();
  spinning.stream(12.0, 0.3F);  // below hover: resting, but the throttle is not zero
  EXPECT_TRUE(spinning.autopilot().armed());
  EXPECT_TRUE(spinning.world().state().uav_contact.resting);
  spinning.stream(10.1, 0.0F);
  EXPECT_FALSE(spinning.autopilot().armed());
}

// ArduCopter SITL: after the bridge's LAND it "disarmed by itself" on touchdown; it stays
// in LAND.
TEST(FirmwareBehaviour, ArduPilotLandDisarmsOnTouchdown) {
  AutopilotBench bench(Autopilot::ArduPilot);
  bench.set_mode(copter::kGuidedNoGps);
  bench.arm();
  bench.stream(1.0, 0.7F);
  ASSERT_EQ(bench.command(mav::mav_cmd::kNavLand)->result, mav::mav_result::kAccepted);
  double touchdown_s = -1.0;
  for (int i = 0; i < 3000 && bench.autopilot().armed(); ++i) {
    bench.tick();
    if (touchdown_s < 0.0 && bench.world().state().uav_contact.resting) touchdown_s = bench.t_s();
  }
  EXPECT_FALSE(bench.autopilot().armed());
  EXPECT_NEAR(disarmed_at(bench.autopilot()), touchdown_s, 0.011);
  EXPECT_EQ(bench.last_statustext(), "Disarming motors");
  EXPECT_EQ(bench.autopilot().mode(), FlightMode::Land);
  EXPECT_TRUE(bench.autopilot().landed_in_land_mode());
}

// --- estimator -------------------------------------------------------------------------

// Until aligned: ArduPilot's EKF_STATUS_REPORT says EKF_UNINITIALIZED and its SYS_STATUS
// neither enables nor passes the AHRS; then attitude, velocity and altitude flags (0xa7, as
// ArduCopter SITL's) and a healthy AHRS. The bridge's tracker reads it so.
TEST(FirmwareBehaviour, EstimatorFlagsAndAhrsHealthOnceAligned) {
  SimFcParams params;
  params.ardupilot.estimator_align_s = 2.0;
  AutopilotBench bench(Autopilot::ArduPilot, ground_world(), params);
  bench.interval(mav::SysStatus::kId, 5e5F);
  bench.interval(mav::EkfStatusReport::kId, 5e5F);
  cover::fc_bridge::EstimatorHealthTracker before(cover::Autopilot::ArduPilot);
  bench.idle(1.0);
  before.on_sys_status(bench.sent<mav::SysStatus>().back());
  before.on_estimator_flags(bench.sent<mav::EkfStatusReport>().back().flags);
  EXPECT_EQ(bench.sent<mav::EkfStatusReport>().back().flags, 1024);
  EXPECT_EQ(bench.sent<mav::SysStatus>().back().onboard_control_sensors_health &
                mav::mav_sys_status_sensor::kAhrs,
            0u);
  EXPECT_FALSE(before.health().attitude_ok);
  EXPECT_EQ(before.health().text, "EKF not initialised");

  bench.idle(1.5);
  cover::fc_bridge::EstimatorHealthTracker after(cover::Autopilot::ArduPilot);
  const auto status = bench.sent<mav::SysStatus>().back();
  after.on_sys_status(status);
  after.on_estimator_flags(bench.sent<mav::EkfStatusReport>().back().flags);
  EXPECT_EQ(bench.sent<mav::EkfStatusReport>().back().flags, 0xa7);
  namespace sensor = mav::mav_sys_status_sensor;
  for (const std::uint32_t bit : {sensor::kGyro3d, sensor::kAccel3d, sensor::kMag3d,
                                  sensor::kAbsolutePressure, sensor::kAhrs}) {
    EXPECT_NE(status.onboard_control_sensors_present & bit, 0u) << bit;
    EXPECT_NE(status.onboard_control_sensors_enabled & bit, 0u) << bit;
    EXPECT_NE(status.onboard_control_sensors_health & bit, 0u) << bit;
  }
  EXPECT_TRUE(after.health().attitude_ok);
  EXPECT_EQ(after.health().text, "attitude, horizontal velocity, vertical velocity, altitude ok");

  // PX4 SITL reported aligned with its first ESTIMATOR_STATUS.
  AutopilotBench px4_bench(Autopilot::Px4);
  px4_bench.tick();
  EXPECT_EQ(px4_bench.sent<mav::EstimatorStatus>().back().flags, 0xa7);
  EXPECT_NE(px4_bench.sent<mav::SysStatus>().back().onboard_control_sensors_health & sensor::kAhrs,
            0u);
}

}  // namespace
