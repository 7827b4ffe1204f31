// The task manager's intake of what the fleet reports (FleetWatch -> FleetIntake ->
// Dispatcher::step): UAV heartbeats, task statuses and UGV IMU samples with foreign ids,
// hostile task ids and states, huge messages, non-finite IMU values, interleaved with
// submissions, aborts and dispatcher steps on an advancing clock.
// Contract: no exception; a final task never changes again; a dispatch goes only to an
// agent that is up and idle; a UGV counts as heard only from a valid sample on its own
// topic; memory for the agents' messages stays bounded; every refusal is counted.
#include <algorithm>
#include <string>
#include <vector>

#include "cover/task_manager/dispatcher.hpp"
#include "cover/task_manager/flyability.hpp"
#include "cover/task_manager/task_store.hpp"
#include "cover/wire/task.hpp"
#include "fleet_intake.hpp"
#include "fuzz_input.hpp"
#include "task_fuzz_support.hpp"

namespace {

using cover::fuzz::FuzzInput;
using cover::fuzz::require;
namespace msg = cover::msg;
namespace tmg = cover::task_manager;

constexpr int kUavs = 3;
constexpr int kUgvs = 3;

msg::Vector3 vec(FuzzInput& in) {
  return {in.real(), in.real(), in.real()};
}

msg::UavStatus uav_status(FuzzInput& in, int topic) {
  msg::UavStatus s;
  s.uav_id = in.byte() % 8 ? static_cast<std::uint32_t>(topic) : in.raw<std::uint32_t>();
  s.task_id = in.byte() % 3 ? cover::fuzz::task_id(in) : "";
  s.task_state = static_cast<msg::TaskState>(in.byte() % 8);
  s.failsafe = static_cast<msg::FailsafeState>(in.byte() % 12);
  return s;
}

msg::TaskStatus task_status(FuzzInput& in) {
  msg::TaskStatus s;
  s.task_id = cover::fuzz::task_id(in);
  s.uav_id = in.byte() % 8 ? in.byte() % kUavs : in.raw<std::uint32_t>();
  s.state = static_cast<msg::TaskState>(in.byte() % 8);
  s.message = in.byte() % 16 ? in.text(40) : std::string(100000, 'm');
  return s;
}

msg::UgvImu ugv_imu(FuzzInput& in, int topic) {
  msg::UgvImu s;
  s.ugv_id = in.byte() % 8 ? static_cast<std::uint32_t>(topic) : in.raw<std::uint32_t>();
  s.specific_force_m_s2 = in.byte() % 2 ? vec(in) : msg::Vector3{0.0, 0.0, 9.81};
  s.angular_velocity_rad_s = in.byte() % 2 ? vec(in) : msg::Vector3{};
  return s;
}

// Once in a final state a task never changes again: in each task's history (every change
// the store ever made, oldest first) nothing follows a final state, but for a submission
// rejected at once, which holds no id: a later submission under it replaces it, and its rows
// go on from rejected to the new one's initial state (rejected again, or queued). Read once per
// input: checking the whole list after every event cost most of the harness's time.
void require_finals_kept(const tmg::TaskStore& store) {
  for (const tmg::TaskRecord& r : store.list(true)) {
    const std::vector<tmg::StateChange> history = store.history(r.task_id);
    for (std::size_t i = 0; i + 1 < history.size(); ++i) {
      if (!tmg::is_final(history[i].to)) continue;
      const tmg::StateChange& next = history[i + 1];
      const bool replaced =
          history[i].to == tmg::TaskState::Rejected && next.from == tmg::TaskState::Rejected;
      require(replaced, "a final task changed again: " + r.task_id);
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzInput in(data, size);
  tmg::TaskStore store(":memory:");
  const tmg::TaskLimits limits;
  tmg::Dispatcher dispatcher(store, limits);
  tmg::FleetIntake intake(kUavs, kUgvs);
  double now_s = 1000.0;
  std::uint64_t refused = 0;
  while (!in.empty()) {
    now_s += in.byte() % 4 == 0 ? 2.0 : 0.05;
    const std::uint8_t event = in.byte() % 6;
    switch (event) {
      case 0: {
        const int topic = static_cast<int>(in.byte() % (kUavs + 1)) - (in.byte() % 8 == 0);
        refused += intake.on_uav_status(uav_status(in, topic), topic, now_s).has_value();
        break;
      }
      case 1:
        refused += intake.on_task_status(task_status(in)).has_value();
        break;
      case 2: {
        const int topic = static_cast<int>(in.byte() % (kUgvs + 1));
        const msg::UgvImu imu = ugv_imu(in, topic);
        const auto before = intake.view().ugv_imu_heard_s;
        const auto why = intake.on_ugv_imu(imu, topic, now_s);
        refused += why.has_value();
        if (why) {
          require(intake.view().ugv_imu_heard_s == before,
                  "a refused IMU sample marked a UGV heard");
        } else {
          require(imu.ugv_id == static_cast<std::uint32_t>(topic) && topic < kUgvs,
                  "a UGV heard from another's topic");
        }
        break;
      }
      case 3: {
        const cover::mission::Task task = cover::wire::from_msg(cover::fuzz::transition_task(in));
        if (!tmg::why_not_recordable(task, "ops", "req")) {
          dispatcher.submit(task, "ops", "req", intake.view(), now_s);
        }
        break;
      }
      case 4:
        dispatcher.abort(cover::fuzz::task_id(in), in.text(20), now_s);
        break;
      default: {
        const tmg::LiveView live = intake.view();
        const tmg::Actions actions = dispatcher.step(live, now_s);
        for (const tmg::Dispatch& d : actions.dispatch) {
          const auto agent = live.agents.find(d.uav_id);
          require(agent != live.agents.end() &&
                      now_s - agent->second.heard_s <= limits.heartbeat_timeout_s,
                  "dispatched to an agent that is not up");
          require(agent->second.task_state != tmg::AgentReport::AgentTask::Pending &&
                      agent->second.task_state != tmg::AgentReport::AgentTask::Running,
                  "dispatched to a busy agent");
        }
        break;
      }
    }
  }
  require_finals_kept(store);
  require(intake.remembered_messages() <= tmg::FleetIntake::kRememberedMessages,
          "the agents' messages grow without bound");
  require(intake.rejections().total() == refused, "a refusal was not counted");
  return 0;
}
