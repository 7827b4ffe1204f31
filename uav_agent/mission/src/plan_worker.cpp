#include "cover/mission/plan_worker.hpp"

#include <memory>
#include <utility>

namespace cover::mission {

const char* to_string(PlanClock clock) {
  switch (clock) {
    case PlanClock::Lockstep:
      return "lockstep";
    case PlanClock::Realtime:
      return "realtime";
  }
  return "unknown";
}

PlanWorker::PlanFunction stage_plan_function(planner::PlannerParams params) {
  // std::function needs a copyable callable: the planner (move-only) lives behind a
  // shared_ptr, used by the worker thread alone.
  auto planner = std::make_shared<planner::StagePlanner>(std::move(params));
  return [planner](const planner::StageProblem& problem, planner::PlanResult& result) {
    planner->plan(problem, result);
  };
}

namespace {

planner::PlanResult sized_result(int pieces) {
  planner::PlanResult result;
  result.trajectory.reserve(pieces);
  return result;
}

}  // namespace

PlanWorker::PlanWorker(PlanFunction plan, int result_pieces)
    : plan_(std::move(plan)),
      done_(sized_result(result_pieces)),
      working_(sized_result(result_pieces)),
      thread_([this] { run(); }) {}

PlanWorker::~PlanWorker() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  work_cv_.notify_one();
  thread_.join();
}

std::uint64_t PlanWorker::request(const planner::StageProblem& problem) {
  std::uint64_t id = 0;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    problem_ = problem;
    id = ++requested_id_;
  }
  work_cv_.notify_one();
  return id;
}

bool PlanWorker::take(std::uint64_t id, planner::PlanResult& result, bool wait) {
  std::unique_lock<std::mutex> lock(mutex_);
  // Ids only grow: a done id beyond `id` means the thread skipped or finished it and moved
  // on, and a newer request supersedes it either way.
  const auto settled = [&] { return done_id_ >= id || requested_id_ > id; };
  if (wait && !settled()) {
    waiting_.store(true);
    done_cv_.wait(lock, settled);
    waiting_.store(false);
  }
  // Superseded even when its plan finished before the newer request came: nobody waits for
  // an older plan once a newer one is asked for.
  if (!takeable(id)) return false;
  std::swap(result, done_);
  taken_ = true;
  return true;
}

bool PlanWorker::ready(std::uint64_t id) {
  const std::lock_guard<std::mutex> lock(mutex_);
  return takeable(id);
}

bool PlanWorker::takeable(std::uint64_t id) const {
  return done_id_ == id && !taken_ && requested_id_ == id;
}

void PlanWorker::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    work_cv_.wait(lock, [&] { return stop_ || requested_id_ != started_id_; });
    if (stop_) return;
    // Only the newest request is planned: an older one nobody will take is skipped.
    started_id_ = requested_id_;
    const planner::StageProblem problem = problem_;
    lock.unlock();
    plan_(problem, working_);
    lock.lock();
    std::swap(done_, working_);
    done_id_ = started_id_;
    taken_ = false;
    done_cv_.notify_all();
  }
}

}  // namespace cover::mission
