// The task manager's checks of a submitted task (cover submit -> cover/manager/request ->
// Dispatcher::submit): tasks from the wire with hostile ids, UGV ids, points and limits,
// against a live fleet of UAVs 0-1 and UGVs 0-2 (UAV 2, UGV 3 are down).
// Contract: a submission that cannot be recorded throws std::invalid_argument and stores
// nothing; any other is stored Queued exactly when it is flyable (every point finite and
// within the limits, limits positive, the chain valid, its UAV and UGVs up) and Rejected
// with a readable reason otherwise; a repeat of an accepted task returns the stored record
// unchanged, one of a submission rejected at once is judged anew and replaces it.
#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include "cover/mission/task_file.hpp"
#include "cover/task_manager/dispatcher.hpp"
#include "cover/task_manager/flyability.hpp"
#include "cover/task_manager/task_store.hpp"
#include "cover/wire/task.hpp"
#include "fuzz_input.hpp"
#include "task_fuzz_support.hpp"

namespace {

using cover::fuzz::require;
namespace tmg = cover::task_manager;

constexpr double kNow_s = 1000.0;

tmg::LiveView live_fleet() {
  tmg::LiveView live;
  for (int u : {0, 1, 2}) {
    tmg::AgentReport& report = live.agents[u];
    report.uav_id = u;
    report.heard_s = u < 2 ? kNow_s : kNow_s - 100.0;  // UAV 2 is silent
  }
  for (int k : {0, 1, 2}) live.ugv_imu_heard_s[k] = kNow_s;
  return live;
}

bool readable(const std::string& text) {
  return !text.empty() && std::all_of(text.begin(), text.end(),
                                      [](char c) { return (c >= 0x20 && c < 0x7f) || c == '\n'; });
}

void check_flyable(const cover::mission::Task& task, const tmg::TaskLimits& limits) {
  cover::mission::validate_task(
      task, 3);  // throws (a violation) if the manager queued a task that cannot fly
  for (const auto& p : task.processes) {
    for (const auto* point : {&p.initial_point_m, &p.transition_point_m, &p.final_point_m}) {
      require(point->allFinite() && std::abs(point->x()) <= limits.max_horizontal_m &&
                  std::abs(point->y()) <= limits.max_horizontal_m && point->z() >= limits.min_z_m &&
                  point->z() <= limits.max_z_m,
              "queued a point beyond the limits");
    }
    require(p.vmax_m_s <= limits.max_vmax_m_s && p.amax_m_s2 <= limits.max_amax_m_s2,
            "queued limits above the vehicle's");
  }
  require(task.uav_id == 0 || task.uav_id == 1, "queued a task for a UAV that is not up");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // One store for many inputs (opening one is the slow part), renewed now and then so that
  // ids repeat within a store but it does not grow without bound.
  static std::unique_ptr<tmg::TaskStore> store;
  static std::unique_ptr<tmg::Dispatcher> dispatcher;
  static int uses = 0;
  const tmg::TaskLimits limits;
  if (!store || ++uses % 64 == 0) {
    dispatcher.reset();
    store = std::make_unique<tmg::TaskStore>(":memory:");
    dispatcher = std::make_unique<tmg::Dispatcher>(*store, limits);
  }
  cover::fuzz::FuzzInput in(data, size);
  const std::string submitter = in.byte() % 8 ? "ops@gs" : in.text(600);
  const std::string request_id = in.byte() % 8 ? "req" : in.text(600);
  const cover::mission::Task task = cover::wire::from_msg(cover::fuzz::transition_task(in));
  const tmg::LiveView live = live_fleet();
  const auto before = store->find(task.task_id);
  const auto recordable = tmg::why_not_recordable(task, submitter, request_id);
  tmg::TaskStore::SubmitResult result;
  try {
    result = dispatcher->submit(task, submitter, request_id, live, kNow_s);
  } catch (const std::invalid_argument& e) {
    require(recordable.has_value(), std::string("refused a recordable submission: ") + e.what());
    require(!store->find(task.task_id) || before, "stored an unrecordable submission");
    return 0;
  }
  require(!recordable, "recorded an unrecordable submission: " + recordable.value_or(""));
  require(result.record.task_id == task.task_id, "the record has another id");
  if (before && before->accepted) {
    require(!result.created && result.record.state == before->state &&
                result.record.reason == before->reason,
            "a repeat changed the stored task");
    return 0;
  }
  // New, or replacing a submission rejected at once (it holds no id).
  require(result.created, "a new task was not created");
  require(result.replaced_rejected == before.has_value(), "replaced_rejected is wrong");
  const auto why = tmg::why_not_flyable(task, live, limits, kNow_s);
  if (result.record.state == tmg::TaskState::Queued) {
    require(!why, "queued a task that is not flyable: " + why.value_or(""));
    check_flyable(task, limits);
  } else {
    require(result.record.state == tmg::TaskState::Rejected,
            "a new task neither queued nor rejected");
    require(why && readable(result.record.reason),
            "rejected without a readable reason: '" + result.record.reason + "'");
  }
  return 0;
}
