#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>

#include "cover/planner/stage_planner.hpp"

namespace cover::mission {

// When a plan requested at control step k is flown: at step k + MissionParams::
// plan_adopt_steps in both clocks; they differ in what that step does when the plan is not
// ready yet.
enum class PlanClock : std::uint8_t {
  // Simulated time (the in-process harness, a lockstep agent): that step waits for the plan,
  // so the flight does not depend on how fast the machine is (bit-identical under load).
  Lockstep = 0,
  // Wall time (a flying agent): the loop never waits; it flies the reference it has and
  // adopts the plan at the first later step at which it is ready (counted as late steps).
  Realtime = 1,
};

const char* to_string(PlanClock clock);

// Plans stages on a thread of its own, so a control step never runs the optimiser. One
// request is in flight at a time: a newer request supersedes an older one not yet taken.
// request() and take() are what the control thread calls: they copy a fixed-size problem
// and swap results, never allocate, and block only when take() is told to wait. The thread
// plans into its results in place: with their trajectories sized once (result_pieces, and
// the caller's result likewise, since take() swaps storage), no plan allocates.
class PlanWorker {
 public:
  // What the thread runs for each request (a StagePlanner's plan(); tests put a gated one).
  using PlanFunction = std::function<void(const planner::StageProblem&, planner::PlanResult&)>;

  // `result_pieces`: the most trajectory pieces a plan writes (PlannerParams::pieces).
  explicit PlanWorker(PlanFunction plan, int result_pieces = 1);
  ~PlanWorker();  // finishes the plan under way, then joins
  PlanWorker(const PlanWorker&) = delete;
  PlanWorker& operator=(const PlanWorker&) = delete;

  // Hands `problem` to the thread; returns the request's id (> 0, increasing).
  std::uint64_t request(const planner::StageProblem& problem);
  // Request `id`'s result, swapped into `result` (whose old contents go back to the worker to
  // be overwritten). With `wait`, blocks until it is done. False when it is not done yet
  // (without `wait`), was superseded by a newer request, or was taken already.
  bool take(std::uint64_t id, planner::PlanResult& result, bool wait);
  // True when request `id`'s result is done, not taken and not superseded.
  bool ready(std::uint64_t id);
  // True while a take() is blocked waiting for its result (what another thread, a test or a
  // watchdog, can see of a lockstep step held up by its plan).
  bool waiting() const { return waiting_.load(); }

 private:
  void run();
  bool takeable(std::uint64_t id) const;  // under mutex_

  PlanFunction plan_;
  std::mutex mutex_;
  std::condition_variable work_cv_;  // a request or stop for the thread
  std::condition_variable done_cv_;  // a result for the control thread
  planner::StageProblem problem_;
  std::uint64_t requested_id_ = 0;
  std::uint64_t started_id_ = 0;
  std::uint64_t done_id_ = 0;
  bool taken_ = false;
  bool stop_ = false;
  std::atomic<bool> waiting_{false};
  planner::PlanResult done_;     // the last result, until taken
  planner::PlanResult working_;  // the thread's own, filled outside the lock
  std::thread thread_;           // last: starts once everything above exists
};

// A StagePlanner on `params` as a PlanFunction, planning into the result it is given
// (throws config::ConfigError when they are invalid).
PlanWorker::PlanFunction stage_plan_function(planner::PlannerParams params);

}  // namespace cover::mission
