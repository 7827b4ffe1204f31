// What `cover fleet` makes of the messages it hears: one row per vehicle or process, the
// clock exchange's names joined to the status of the same id, ages and staleness.
#include "fleet_view.hpp"

#include <gtest/gtest.h>

namespace cover::cli {
namespace {

constexpr std::int64_t kS = 1'000'000'000;

const FleetRow* find(const std::vector<FleetRow>& rows, FleetKind kind,
                     std::optional<std::uint32_t> id = std::nullopt) {
  for (const FleetRow& r : rows) {
    if (r.kind == kind && r.id == id) return &r;
  }
  return nullptr;
}

TEST(FleetView, UavStatusAndItsBridgeMakeTwoRowsTheUavShowingTheAutopilot) {
  FleetView view;
  msg::UavStatus uav;
  uav.uav_id = 1;
  uav.task_id = "scenario2";
  uav.task_state = msg::TaskState::TASK_RUNNING;
  uav.stage = msg::Stage::STAGE_TRANSITION;
  uav.process_count = 2;
  uav.failsafe = msg::FailsafeState::FAILSAFE_IMU_HOLD;
  uav.armed = true;
  view.heard(uav, {{"uav_id", 1}}, 10 * kS);
  msg::FcState fc;
  fc.uav_id = 1;
  fc.link_ok = true;
  fc.autopilot = msg::FcAutopilot::FC_AUTOPILOT_PX4;
  fc.mode_name = "OFFBOARD";
  fc.armed = true;
  fc.offboard_ready = true;
  view.heard(fc, {}, 10 * kS);
  view.heard_peer("uav1-nx/cover-uav-agent-1", 10 * kS);

  const auto rows = view.rows(10 * kS + kS / 2);
  ASSERT_EQ(rows.size(), 2u);
  const FleetRow* r = find(rows, FleetKind::UavAgent, 1);
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->state, "running transition 1/2, armed");
  EXPECT_EQ(r->failsafe, "imu_hold");
  EXPECT_EQ(r->task, "scenario2");
  EXPECT_EQ(r->autopilot, "px4 OFFBOARD armed");
  EXPECT_EQ(r->processes, std::vector<std::string>{"uav1-nx/cover-uav-agent-1"});
  EXPECT_DOUBLE_EQ(r->age_s, 0.5);
  EXPECT_FALSE(r->stale);
  EXPECT_EQ(r->detail["uav_id"], 1);
  const FleetRow* bridge = find(rows, FleetKind::FcBridge, 1);
  ASSERT_NE(bridge, nullptr);
  EXPECT_EQ(bridge->state, "offboard-ready");
  EXPECT_EQ(bridge->failsafe, "none");
}

TEST(FleetView, AVehicleTurnsStaleByItsStatusNotByItsClockAnswers) {
  FleetView view;
  msg::UavStatus uav;
  view.heard(uav, {}, 0);
  // Its loop hung, its clock responder still answers: the status's age counts.
  view.heard_peer("h/cover-uav-agent-0", 5 * kS);
  const auto rows = view.rows(5 * kS);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_DOUBLE_EQ(rows[0].age_s, 5.0);
  EXPECT_TRUE(rows[0].stale);
  EXPECT_EQ(rows[0].state, "idle, disarmed");
  EXPECT_EQ(rows[0].autopilot, "-");
}

TEST(FleetView, TheTaskManagerIsNamedByTheClockExchangeAndDescribedByItsAnswer) {
  FleetView view(1.5);
  view.heard_peer("gcs/cover-task-manager", 1 * kS);
  msg::ManagerReply reply;
  msg::ManagedTask queued;
  queued.task_id = "a";
  queued.state = msg::ManagedTaskState::MANAGED_QUEUED;
  msg::ManagedTask running;
  running.task_id = "b";
  running.uav_id = 2;
  running.state = msg::ManagedTaskState::MANAGED_RUNNING;
  reply.tasks = {queued, running};
  view.heard(reply, {}, 2 * kS);
  const auto rows = view.rows(2 * kS);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].kind, FleetKind::TaskManager);
  EXPECT_EQ(rows[0].processes, std::vector<std::string>{"gcs/cover-task-manager"});
  EXPECT_EQ(rows[0].state, "1 queued, 1 in flight");
  EXPECT_EQ(rows[0].task, "b (UAV 2)");
  EXPECT_EQ(rows[0].messages, 2u);
  EXPECT_DOUBLE_EQ(rows[0].stale_after_s, 3.0);
}

TEST(FleetView, AStatusWithoutANameStaysApartWhenTwoProcessesOfItsKindAreNamed) {
  FleetView view;
  msg::SimClock tick;
  tick.mode = msg::ClockMode::CLOCK_MODE_LOCKSTEP;
  tick.stamp_ns = 12'345'000'000;
  view.heard(tick, {}, 0);
  EXPECT_EQ(view.rows(0).at(0).state, "lockstep, t 12.3 s");
  EXPECT_TRUE(view.rows(0).at(0).processes.empty());
  view.heard_peer("a/cover-sim", 0);
  ASSERT_EQ(view.rows(0).size(), 1u);  // joined to the one simulator named
  EXPECT_EQ(view.rows(0).at(0).state, "lockstep, t 12.3 s");
  view.heard_peer("b/cover-sim", 0);
  EXPECT_EQ(view.rows(0).size(), 3u);
}

TEST(FleetView, OneIdClaimedByTwoHostsListsBothAndUnknownNamesAreProcesses) {
  FleetView view;
  view.heard_peer("ugv1-pi/cover-ugv-agent-1", 0);
  view.heard_peer("spare-pi/cover-ugv-agent-1", 0);
  view.heard_peer("x/cover-ugv-agent-", 0);
  view.heard_peer("x/cover-ugv-agent-99999999999999", 0);
  view.heard_peer("laptop/my-tool", 0);
  const auto rows = view.rows(0);
  const FleetRow* ugv = find(rows, FleetKind::UgvAgent, 1);
  ASSERT_NE(ugv, nullptr);
  EXPECT_EQ(ugv->processes.size(), 2u);
  EXPECT_EQ(ugv->state, "still listening: no status heard yet");
  std::size_t processes = 0;
  for (const FleetRow& r : rows) processes += r.kind == FleetKind::Process ? 1 : 0;
  EXPECT_EQ(processes, 3u);
}

// A listing ends when every process heard is described: before, it would print a state it
// has not had time to hear ("heard in the clock exchange only" for a UAV agent whose
// status had not come yet, "did not answer the query" for a task manager asked too early).
TEST(FleetView, AListingIsSettledOnceEveryProcessHeardIsDescribedAndNamed) {
  FleetView view;
  EXPECT_TRUE(view.settled(0, kS)) << "nothing heard: nothing to wait for";
  view.heard_peer("h/cover-uav-agent-0", 1 * kS);
  EXPECT_FALSE(view.settled(1 * kS, kS)) << "named, its status not heard";
  EXPECT_EQ(view.rows(1 * kS).at(0).state, "still listening: no status heard yet");
  msg::UavStatus uav;
  view.heard(uav, {}, 2 * kS);
  EXPECT_TRUE(view.settled(2 * kS, kS));
  EXPECT_EQ(view.rows(2 * kS).at(0).state, "idle, disarmed");

  // The task manager: named by its clock requests, described by its answer to the query.
  view.heard_peer("h/cover-task-manager", 3 * kS);
  EXPECT_FALSE(view.settled(3 * kS, kS));
  const auto rows = view.rows(3 * kS);
  const FleetRow* manager = find(rows, FleetKind::TaskManager);
  ASSERT_NE(manager, nullptr);
  EXPECT_EQ(manager->state, "still listening: no answer to the query yet");
  view.heard(msg::ManagerReply{}, {}, 4 * kS);
  EXPECT_TRUE(view.settled(4 * kS, kS));

  // A process known only by its clock requests has nothing more to say.
  view.heard_peer("laptop/my-tool", 5 * kS);
  EXPECT_TRUE(view.settled(5 * kS, kS));
}

TEST(FleetView, ADiscoveredWriterIsARowStillListenedToUntilItsStatusComes) {
  FleetView view;
  view.discovered(FleetKind::UgvAgent, 3, 1 * kS);
  view.discovered(FleetKind::UgvAgent, 3, 2 * kS);  // still the first discovery
  view.discovered(FleetKind::Sim, std::nullopt, 1 * kS);
  EXPECT_FALSE(view.settled(9 * kS, kS));
  const auto rows = view.rows(2 * kS);
  ASSERT_EQ(rows.size(), 2u);
  const FleetRow* ugv = find(rows, FleetKind::UgvAgent, 3);
  ASSERT_NE(ugv, nullptr);
  EXPECT_EQ(ugv->state, "still listening: no status heard yet");
  EXPECT_DOUBLE_EQ(ugv->age_s, 1.0) << "since its discovery";
  EXPECT_EQ(ugv->messages, 0u);
  msg::UgvStatus status;
  status.ugv_id = 3;
  view.heard(status, {}, 3 * kS);
  msg::SimClock tick;
  view.heard(tick, {}, 3 * kS);
  // Described, not named yet: waited for within the naming grace, from its discovery.
  EXPECT_FALSE(view.settled(3 * kS, 5 * kS));
  EXPECT_TRUE(view.settled(3 * kS, 2 * kS)) << "past the grace: listed unnamed";
  view.heard_peer("h/cover-ugv-agent-3", 3 * kS);
  view.heard_peer("h/cover-sim", 3 * kS);
  EXPECT_TRUE(view.settled(3 * kS, 5 * kS));
  ASSERT_EQ(view.rows(3 * kS).size(), 2u) << "the simulator's clock joined to its name";
}

TEST(FleetView, AnUnnamedRowSettlesAfterTheNamingGrace) {
  FleetView view;
  msg::SimClock tick;  // no UAV agent asks the simulator: nobody names it
  view.heard(tick, {}, 1 * kS);
  EXPECT_FALSE(view.settled(1 * kS + kS / 2, kS));
  EXPECT_TRUE(view.settled(2 * kS, kS));
  EXPECT_TRUE(view.rows(2 * kS).at(0).processes.empty());
}

TEST(FleetView, TableAndJsonCarryEveryRow) {
  FleetView view;
  msg::UgvStatus ugv;
  ugv.ugv_id = 0;
  ugv.healthy = true;
  ugv.imu_rate_hz = 199.6;
  ugv.source = "sim-shm";
  view.heard(ugv, {{"ugv_id", 0}}, 0);
  const auto rows = view.rows(4 * kS);
  const std::string table = fleet_table(rows);
  EXPECT_NE(table.find("KIND"), std::string::npos);
  EXPECT_NE(table.find("ugv-agent"), std::string::npos) << table;
  EXPECT_NE(table.find("healthy, IMU 200 Hz (sim-shm)"), std::string::npos) << table;
  EXPECT_NE(table.find("4.0 s STALE"), std::string::npos) << table;
  const auto json = fleet_json(rows);
  ASSERT_EQ(json.size(), 1u);
  EXPECT_EQ(json[0]["kind"], "ugv-agent");
  EXPECT_EQ(json[0]["id"], 0);
  EXPECT_EQ(json[0]["stale"], true);
  EXPECT_EQ(json[0]["last"]["ugv_id"], 0);
  EXPECT_TRUE(json[0]["processes"].empty());
}

}  // namespace
}  // namespace cover::cli
