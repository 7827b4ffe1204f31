// What the real firmware demands of the bridge (docs/autopilots.md): streams asked for,
// PX4's EVENTs read, the parameters COVER depends on checked, the estimator's state, the
// command timeout on a loaded companion. The logic without sockets: frames in, frames out.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "bridge_rig.hpp"
#include "cover/fc_bridge/estimator_health.hpp"
#include "cover/fc_bridge/parameter_check.hpp"
#include "cover/fc_bridge/px4_events.hpp"
#include "cover/fc_bridge/stream_monitor.hpp"
#include "cover/mavlink/event_messages.hpp"
#include "cover/mavlink/parameter_messages.hpp"
#include "cover/mavlink/state_messages.hpp"
#include "fake_autopilot.hpp"

namespace cover::fc_bridge {
namespace {

namespace mav = cover::mavlink;
using test::BridgeRig;
using test::commands;
using test::decoded;

std::vector<mav::CommandLong> stream_requests(const BridgeRig& rig) {
  return rig.sent_commands(mav::mav_cmd::kSetMessageInterval);
}

bool asked_for(const BridgeRig& rig, std::uint32_t id, double interval_us) {
  for (const auto& c : stream_requests(rig)) {
    if (c.param[0] == static_cast<float>(id) && c.param[1] == static_cast<float>(interval_us)) {
      return true;
    }
  }
  return false;
}

TEST(Streams, ArduPilotIsAskedForWhatTheBridgeReadsOnceItIsFound) {
  BridgeRig rig(Autopilot::ArduPilot);
  rig.run(2.0);
  EXPECT_TRUE(asked_for(rig, mav::HighresImu::kId, 10000.0));  // 100 Hz
  EXPECT_TRUE(asked_for(rig, mav::ExtendedSysState::kId, 200000.0));
  EXPECT_TRUE(asked_for(rig, mav::SysStatus::kId, 500000.0));
  EXPECT_TRUE(asked_for(rig, mav::BatteryStatus::kId, 1e6));
  EXPECT_TRUE(asked_for(rig, mav::EkfStatusReport::kId, 1e6));
  EXPECT_FALSE(asked_for(rig, mav::EstimatorStatus::kId, 1e6));  // PX4's, not ArduPilot's
  EXPECT_FALSE(asked_for(rig, mav::AttitudeTarget::kId, 0.0));   // 0 Hz: not asked
  for (const auto& c : stream_requests(rig)) EXPECT_EQ(c.target_system, test::kSys);
}

TEST(Streams, AStreamThatDoesNotComeIsNamedAskedAgainAndClearedWhenItComes) {
  BridgeRig rig(Autopilot::ArduPilot);  // the rig's autopilot sends no HIGHRES_IMU
  rig.run(3.0);
  const std::size_t asked_first = stream_requests(rig).size();
  FcStatus s = rig.bridge.state(rig.t);
  EXPECT_NE(s.streams_missing.find("HIGHRES_IMU (asked 100 Hz"), std::string::npos)
      << s.streams_missing;
  rig.collect_notices();
  EXPECT_TRUE(rig.noticed("streams asked of the autopilot not arriving: "));
  rig.run(6.0);
  EXPECT_GT(stream_requests(rig).size(), asked_first);  // asked again (stream_reask_s 5 s)
  // Every stream arrives from now on, at its rate.
  for (int i = 0; i < 400; ++i) {
    rig.step();
    rig.bridge.on_frame(rig.autopilot.imu(-9.81F), rig.t);
    if (i % 20 == 0) {
      rig.bridge.on_frame(rig.autopilot.send(mav::SysStatus{}), rig.t);
      rig.bridge.on_frame(rig.autopilot.send(mav::BatteryStatus{}), rig.t);
      rig.bridge.on_frame(rig.autopilot.send(mav::EkfStatusReport{}), rig.t);
    }
  }
  s = rig.bridge.state(rig.t);
  EXPECT_EQ(s.streams_missing, "");
  for (const StreamState& stream : s.streams) {
    if (std::string(stream.request.name) == "HIGHRES_IMU") {
      EXPECT_NEAR(stream.measured_hz, 100.0, 5.0);
      EXPECT_TRUE(stream.arriving);
    }
  }
  rig.collect_notices();
  EXPECT_TRUE(rig.noticed("every stream asked of the autopilot arrives"));
}

TEST(Streams, AOneHertzStreamMeasuresOneHertz) {
  StreamMonitor monitor({{mav::BatteryStatus::kId, "BATTERY_STATUS", 1.0}}, 5.0);
  monitor.restart(0.0);
  ASSERT_TRUE(monitor.next_request(0.0).has_value());
  monitor.on_result(CommandOutcome::Accepted, "accepted", 0.01);
  for (int second = 0; second <= 6; ++second) monitor.on_frame(mav::BatteryStatus::kId, second);
  const auto states = monitor.states(6.0);
  ASSERT_EQ(states.size(), 1U);
  EXPECT_NEAR(states[0].measured_hz, 1.0, 1e-9);  // each frame counted once
  EXPECT_TRUE(states[0].arriving);
  EXPECT_EQ(monitor.missing_summary(6.0), "");
  // Missing after 5 of its periods without a frame.
  EXPECT_NE(monitor.missing_summary(12.0).find("BATTERY_STATUS (asked 1 Hz, none for 6.0 s)"),
            std::string::npos);
}

// LOCAL_POSITION_NED is optional (a vehicle without a position estimate has none): asked,
// asked again while it does not come, but never named missing; a required one is.
TEST(Streams, AnOptionalStreamIsAskedButNeverNamedMissing) {
  StreamMonitor monitor({{mav::LocalPositionNed::kId, "LOCAL_POSITION_NED", 50.0, true},
                         {mav::BatteryStatus::kId, "BATTERY_STATUS", 1.0}},
                        5.0);
  monitor.restart(0.0);
  for (int i = 0; i < 2; ++i) {
    ASSERT_TRUE(monitor.next_request(0.0).has_value());
    monitor.on_result(CommandOutcome::Accepted, "accepted", 0.01);
  }
  EXPECT_EQ(monitor.missing_summary(10.0), "BATTERY_STATUS (asked 1 Hz, none for 10.0 s)");
  const auto again = monitor.next_request(10.0);
  ASSERT_TRUE(again.has_value());
  EXPECT_EQ(again->param[0], static_cast<float>(mav::LocalPositionNed::kId));
  const auto plan = stream_plan(Autopilot::ArduPilot, [] {
    StreamRates rates;
    rates.local_position_ned_hz = 50.0;
    return rates;
  }());
  ASSERT_FALSE(plan.empty());
  EXPECT_EQ(plan.back().message_id, mav::LocalPositionNed::kId);
  EXPECT_TRUE(plan.back().optional);
  EXPECT_FALSE(plan.front().optional);
}

TEST(Streams, AskedAgainAfterTheAutopilotComesBack) {
  BridgeRig rig(Autopilot::Px4);
  rig.run(2.0);
  const std::size_t before = stream_requests(rig).size();
  rig.heartbeats = false;  // a reboot: silent, then back
  rig.run(3.0);
  rig.heartbeats = true;
  rig.run(2.0);
  EXPECT_GE(stream_requests(rig).size(), 2 * before - 1);
}

TEST(Px4Events, IdsAreTheNamespaceAndTheNamesFnv1aHash) {
  // From PX4's own metadata (all_events.json: component 1, sub-ids 133277 and 3087815).
  EXPECT_EQ(px4_event_id("commander_arm_denied_resolve_failures"), (1U << 24) | 133277U);
  EXPECT_EQ(px4_event_id("check_modes_offboard_signal"), (1U << 24) | 3087815U);
}

mav::Event event(const char* name, std::initializer_list<std::uint8_t> arguments,
                 std::uint8_t level = 4) {
  mav::Event e;
  e.id = px4_event_id(name);
  e.log_levels = static_cast<std::uint8_t>((level << 4) | level);
  std::size_t i = 0;
  for (const std::uint8_t a : arguments) e.arguments[i++] = a;
  return e;
}

TEST(Px4Events, TextsWithTheirArguments) {
  EXPECT_EQ(describe_px4_event(event("commander_arm_denied_resolve_failures", {})).text,
            "Arming denied: Resolve system health failures first");
  EXPECT_EQ(describe_px4_event(event("commander_armed_by", {4})).text, "Armed by external command");
  EXPECT_EQ(describe_px4_event(event("commander_disarmed_by", {7})).text,
            "Disarmed by preflight inaction");
  // uint32 arg0, then the failsafe action (8: Descend).
  EXPECT_EQ(describe_px4_event(event("commander_failsafe_enter_generic", {0, 0, 0, 0, 8})).text,
            "Failsafe activated: switching to Descend");
  // "{4}: switching to {2} in {3} seconds": uint32, action 7 (Land), uint16 5, cause 2.
  EXPECT_EQ(
      describe_px4_event(event("commander_failsafe_enter_hold", {0, 0, 0, 0, 7, 5, 0, 2})).text,
      "GCS connection loss: switching to Land in 5 seconds");
  const EventText unknown = describe_px4_event(event("not_a_px4_event", {}));
  EXPECT_FALSE(unknown.known);
  EXPECT_NE(unknown.text.find("PX4 event 0x"), std::string::npos);
  EXPECT_FALSE(describe_px4_event(event("commander_takeoff_detected", {}, 8)).for_operator);
}

TEST(Px4Events, ARefusedArmSaysWhyInTheOperatorsAnswer) {
  BridgeRig rig(Autopilot::Px4);
  rig.obey = false;
  rig.run(1.0);
  rig.bridge.on_operator_request(OperatorCommand::Arm, "arm-1", rig.t);
  // PX4: the ACK, then its reasons as EVENTs (never STATUSTEXT).
  rig.bridge.on_frame(rig.autopilot.ack(mav::mav_cmd::kComponentArmDisarm,
                                        mav::mav_result::kTemporarilyRejected, test::kSys, 191),
                      rig.t);
  mav::Event reason = event("commander_arm_denied_resolve_failures", {});
  reason.sequence = 10;
  rig.bridge.on_frame(rig.autopilot.send(reason), rig.t + 0.01);
  mav::Event signal = event("check_modes_offboard_signal", {});
  signal.sequence = 11;
  rig.bridge.on_frame(rig.autopilot.send(signal), rig.t + 0.02);
  rig.bridge.on_frame(rig.autopilot.send(signal), rig.t + 0.03);  // sent again: not news
  EXPECT_TRUE(rig.bridge.replies().empty());                      // waits a moment for the reason
  rig.run(0.5);
  auto& replies = rig.bridge.replies();
  ASSERT_EQ(replies.size(), 1U);
  EXPECT_EQ(replies[0].outcome, CommandOutcome::Refused);
  EXPECT_EQ(replies[0].message,
            "arm: refused (temporarily rejected); the autopilot says: Arming denied: Resolve "
            "system health failures first; No offboard signal");
  EXPECT_EQ(rig.bridge.state(rig.t).status_text, "No offboard signal");
}

void answer_all(BridgeRig& rig, double seconds) {
  rig.run(seconds);
  rig.collect_notices();
}

TEST(Parameters, ArduPilotAngleBoostOnHoldsTasksWithTheReason) {
  BridgeRig rig(Autopilot::ArduPilot);
  rig.parameters = {{"ATC_ANGLE_BOOST", 1.0F}, {"GUID_OPTIONS", 8.0F},    {"GUID_TIMEOUT", 3.0F},
                    {"FS_THR_ENABLE", 0.0F},   {"MOT_THST_HOVER", 0.39F}, {"DISARM_DELAY", 10.0F},
                    {"SYSID_THISMAV", 7.0F}};  // before 4.7: MAV_SYSID unanswered
  answer_all(rig, 8.0);
  const FcStatus s = rig.bridge.state(rig.t);
  EXPECT_EQ(s.flight_blocker,
            "autopilot parameter ATC_ANGLE_BOOST is 1, COVER needs 0: ArduPilot multiplies the "
            "thrust by 1/cos(tilt); COVER's thrust is already along the body axis, so it would "
            "be compensated twice");
  EXPECT_DOUBLE_EQ(s.auto_disarm_s, 10.0);
  bool sysid_found = false;
  for (const ParameterFinding& f : s.parameters) {
    if (f.name == "SYSID_THISMAV") sysid_found = f.known && f.value == 7.0;
    if (f.name == "GUID_OPTIONS") {
      EXPECT_TRUE(f.ok);
    }
  }
  EXPECT_TRUE(sysid_found) << "the old name is tried when the new one is not answered";
  EXPECT_TRUE(rig.noticed("COVER's tasks are held: autopilot parameter ATC_ANGLE_BOOST is 1"));
  // Put right by the operator: read again within param_refresh_s, the hold ends.
  rig.parameters["ATC_ANGLE_BOOST"] = 0.0F;
  answer_all(rig, 12.0);
  EXPECT_EQ(rig.bridge.state(rig.t).flight_blocker, "");
  EXPECT_TRUE(rig.noticed("no autopilot parameter holds COVER's flights any more"));
}

const ParameterFinding* finding(const FcStatus& s, const std::string& name) {
  for (const ParameterFinding& f : s.parameters) {
    if (f.name == name) return &f;
  }
  return nullptr;
}

// ArduCopter lands by itself when the bridge dies only if its GCS failsafe watches the
// bridge's HEARTBEAT: FS_GCS_ENABLE 5 (Land), a short FS_GCS_TIMEOUT, MAV_GCS_SYSID the
// system id the bridge speaks as (the vehicle's). Advisory: wrong, they hold no task.
TEST(Parameters, ArduPilotGcsFailsafeMustWatchTheBridgesHeartbeat) {
  BridgeRig rig(Autopilot::ArduPilot);
  rig.parameters = {{"ATC_ANGLE_BOOST", 0.0F},
                    {"GUID_OPTIONS", 8.0F},
                    {"FS_GCS_ENABLE", 5.0F},
                    {"FS_GCS_TIMEOUT", 5.0F},
                    {"MAV_GCS_SYSID", static_cast<float>(test::kSys)}};
  answer_all(rig, 8.0);
  FcStatus s = rig.bridge.state(rig.t);
  for (const char* name : {"FS_GCS_ENABLE", "FS_GCS_TIMEOUT", "MAV_GCS_SYSID"}) {
    const ParameterFinding* f = finding(s, name);
    ASSERT_NE(f, nullptr) << name;
    EXPECT_TRUE(f->known && f->ok) << name << " = " << f->value;
    EXPECT_EQ(f->weight, ParameterWeight::Advisory) << name;
  }
  // ArduPilot's defaults: no GCS failsafe, the ground station's id 255 watched; and an RTL,
  // which needs a position, and a timeout that leaves the UAV drifting for 10 s.
  for (const auto& [name, value] :
       std::map<std::string, float>{{"FS_GCS_ENABLE", 0.0F}, {"MAV_GCS_SYSID", 255.0F}}) {
    rig.parameters[name] = value;
  }
  rig.parameters["FS_GCS_TIMEOUT"] = 10.0F;
  answer_all(rig, 12.0);  // read again within param_refresh_s
  s = rig.bridge.state(rig.t);
  for (const char* name : {"FS_GCS_ENABLE", "FS_GCS_TIMEOUT", "MAV_GCS_SYSID"}) {
    const ParameterFinding* f = finding(s, name);
    ASSERT_NE(f, nullptr) << name;
    EXPECT_TRUE(f->known) << name;
    EXPECT_FALSE(f->ok) << name << " = " << f->value;
  }
  EXPECT_EQ(s.flight_blocker, "");         // advisory only
  rig.parameters["FS_GCS_ENABLE"] = 1.0F;  // RTL
  answer_all(rig, 12.0);
  EXPECT_FALSE(finding(rig.bridge.state(rig.t), "FS_GCS_ENABLE")->ok);
}

// Before ArduPilot 4.7 the watched id is SYSID_MYGCS; a bridge given its own system id in
// its settings is watched under that id, not the vehicle's.
TEST(Parameters, TheWatchedIdIsTheOneTheBridgeSpeaksAsUnderEitherName) {
  BridgeConfig config = BridgeRig::config(Autopilot::ArduPilot, false);
  config.params.system_id = 42;
  BridgeRig rig(config);
  rig.parameters = {{"SYSID_MYGCS", static_cast<float>(test::kSys)}};  // MAV_GCS_SYSID unanswered
  answer_all(rig, 8.0);
  const ParameterFinding* f = finding(rig.bridge.state(rig.t), "SYSID_MYGCS");
  ASSERT_NE(f, nullptr) << "the old name is tried when the new one is not answered";
  EXPECT_TRUE(f->known);
  EXPECT_FALSE(f->ok) << "the vehicle's id, but the bridge speaks as 42";
  rig.parameters["SYSID_MYGCS"] = 42.0F;
  answer_all(rig, 12.0);
  EXPECT_TRUE(finding(rig.bridge.state(rig.t), "SYSID_MYGCS")->ok);
}

// A value read before the bridge knew its own system id is judged again once it does.
TEST(Parameters, AValueAgainstTheLinkIsJudgedAgainWhenTheLinkIsKnown) {
  ParameterCheck check(parameter_rules(Autopilot::ArduPilot), mav::ParamEncoding::CCast, 1.0, 2,
                       10.0);
  check.restart(0.0);
  mav::ParamValue value;
  value.param_id = mav::param_id_from("MAV_GCS_SYSID");
  value.param_type = mav::mav_param_type::kInt16;
  value.param_value = 3.0F;
  check.on_value(value, 0.1);
  const auto judged = [&check] {
    for (const ParameterFinding& f : check.findings()) {
      if (f.name == "MAV_GCS_SYSID") return f.ok;
    }
    return false;
  };
  EXPECT_FALSE(judged());  // no system id yet: not the bridge's
  check.set_context(ParameterContext{3});
  EXPECT_TRUE(judged());
  check.set_context(ParameterContext{4});
  EXPECT_FALSE(judged());
}

TEST(Parameters, GuidedThrustNotSelectedIsBlocking) {
  BridgeRig rig(Autopilot::ArduPilot);
  rig.parameters = {{"ATC_ANGLE_BOOST", 0.0F}, {"GUID_OPTIONS", 0.0F}};
  answer_all(rig, 8.0);
  EXPECT_NE(rig.bridge.state(rig.t).flight_blocker.find("GUID_OPTIONS is 0, COVER needs bit 3"),
            std::string::npos);
}

TEST(Parameters, Px4DisarmDelayAndAbsentParameters) {
  BridgeRig rig(Autopilot::Px4);
  rig.parameters = {{"COM_DISARM_PRFLT", 10.0F}, {"COM_OF_LOSS_T", 1.0F}, {"NAV_DLL_ACT", 2.0F}};
  answer_all(rig, 8.0);
  const FcStatus s = rig.bridge.state(rig.t);
  EXPECT_DOUBLE_EQ(s.auto_disarm_s, 11.0);  // + PX4's 1 s spool-up
  EXPECT_EQ(s.flight_blocker, "");          // advisory only
  for (const ParameterFinding& f : s.parameters) {
    if (f.name == "NAV_DLL_ACT") {
      EXPECT_FALSE(f.ok);
      EXPECT_EQ(f.weight, ParameterWeight::Advisory);
    }
    if (f.name == "COM_OBL_RC_ACT") {
      EXPECT_TRUE(f.absent);  // asked param_read_tries times, never answered
      EXPECT_FALSE(f.ok);
    }
  }
}

double finding_value(const FcStatus& s, const std::string& name) {
  for (const ParameterFinding& f : s.parameters) {
    if (f.name == name && f.known) return f.value;
  }
  return -999.0;
}

// PX4 copies an integer parameter's bytes into PARAM_VALUE's float (seen from real PX4 SITL:
// COM_RC_IN_MODE 1 arrived as 1.4e-45); ArduPilot converts the value.
TEST(Parameters, Px4SendsIntegersBytewiseArduPilotAsValues) {
  for (const Autopilot kind : {Autopilot::Px4, Autopilot::ArduPilot}) {
    BridgeRig rig(kind);
    rig.run(1.0);
    const bool px4 = kind == Autopilot::Px4;
    mav::ParamValue value;
    value.param_id = mav::param_id_from(px4 ? "NAV_DLL_ACT" : "FS_THR_ENABLE");
    value.param_type = px4 ? mav::mav_param_type::kInt32 : mav::mav_param_type::kInt8;
    value.param_value = mav::param_field_of(
        2.0, value.param_type, px4 ? mav::ParamEncoding::Bytewise : mav::ParamEncoding::CCast);
    if (px4) {
      EXPECT_LT(value.param_value, 1e-40F);  // the bytes of int 2, as a float: denormal
    } else {
      EXPECT_EQ(value.param_value, 2.0F);
    }
    rig.bridge.on_frame(rig.autopilot.send(value), rig.t);
    EXPECT_EQ(finding_value(rig.bridge.state(rig.t), px4 ? "NAV_DLL_ACT" : "FS_THR_ENABLE"), 2.0);
  }
}

TEST(Parameters, TheEstimateStartsAtTheAutopilotsHoverThrustWhenAsked) {
  BridgeConfig config = BridgeRig::config(Autopilot::ArduPilot, false);
  config.params.hover_thrust_from_autopilot = true;
  BridgeRig rig(config);
  rig.parameters = {{"MOT_THST_HOVER", 0.39F}};
  answer_all(rig, 4.0);
  EXPECT_NEAR(rig.bridge.state(rig.t).hover_thrust, 0.39, 1e-6);
  EXPECT_TRUE(rig.noticed("hover thrust estimate starts at the autopilot's MOT_THST_HOVER 0.390"));
}

TEST(Estimator, Px4FlagsAndSensorHealthInWords) {
  EstimatorHealthTracker px4(Autopilot::Px4);
  EXPECT_FALSE(px4.health().reported);
  mav::SysStatus status;
  namespace bit = mav::mav_sys_status_sensor;
  status.onboard_control_sensors_present = bit::kGyro3d | bit::kMag3d | bit::kAhrs;
  status.onboard_control_sensors_enabled = status.onboard_control_sensors_present;
  status.onboard_control_sensors_health = bit::kGyro3d | bit::kAhrs;
  px4.on_sys_status(status);
  px4.on_estimator_flags(mav::estimator_flags::kAttitude | mav::estimator_flags::kVelocityVert);
  EstimatorHealth h = px4.health();
  EXPECT_TRUE(h.attitude_ok);
  EXPECT_EQ(h.text, "attitude, vertical velocity ok; magnetometer unhealthy");
  px4.on_estimator_flags(0);  // not aligned (the deck turned faster than 15 deg/s)
  h = px4.health();
  EXPECT_FALSE(h.attitude_ok);
  EXPECT_EQ(h.text, "no valid estimate; attitude not aligned; magnetometer unhealthy");
}

TEST(Estimator, ArduPilotUninitialisedEkfIsNotReady) {
  EstimatorHealthTracker ap(Autopilot::ArduPilot);
  ap.on_estimator_flags(1024 | mav::estimator_flags::kAttitude);
  EXPECT_FALSE(ap.health().attitude_ok);
  EXPECT_EQ(ap.health().text, "EKF not initialised");
}

TEST(CommandTimeout, ABridgeDescheduledPastTheTimeoutWaitsOnePassForTheQueuedCommands) {
  BridgeRig rig;
  rig.run(1.0);
  rig.flying();
  rig.run(0.5);
  // The whole process stalls 150 ms (a loaded companion): no tick, no command delivered.
  rig.t += 0.15;
  rig.take(rig.bridge.tick(rig.t));  // the housekeeping pass wakes first
  EXPECT_TRUE(rig.sent_commands(mav::mav_cmd::kNavLand).empty())
      << "a stall of the bridge itself is not the agent's silence";
  rig.run(0.5);  // the queued commands arrive, the stream goes on
  EXPECT_TRUE(rig.sent_commands(mav::mav_cmd::kNavLand).empty());
  rig.collect_notices();
  EXPECT_TRUE(rig.noticed("housekeeping 150 ms late"));
}

TEST(CommandTimeout, ARealSilenceStillLandsWithinTheTimeoutAndOnePass) {
  BridgeRig rig;
  rig.run(1.0);
  rig.flying();
  rig.run(0.5);
  rig.agent_alive = false;
  const double last = rig.t;
  while (rig.sent_commands(mav::mav_cmd::kNavLand).empty() && rig.t < last + 1.0) rig.step();
  EXPECT_LE(rig.t - last, 0.1 + 0.02 + 1e-9);
}

}  // namespace
}  // namespace cover::fc_bridge
