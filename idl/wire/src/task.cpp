#include "cover/wire/task.hpp"

#include <algorithm>
#include <limits>

#include "cover/wire/eigen.hpp"
#include "cover/wire/enums.hpp"

namespace cover::wire {

msg::TransitionTask to_msg(const mission::Task& task, double stamp_s) {
  msg::TransitionTask m;
  m.task_id = task.task_id;
  m.uav_id = static_cast<std::uint32_t>(std::max(task.uav_id, 0));
  m.stamp_ns = to_stamp_ns(stamp_s);
  for (const mission::TransitionProcess& p : task.processes) {
    msg::TransitionProcess w;
    w.from_ugv = static_cast<std::uint32_t>(std::max(p.from_ugv, 0));
    w.to_ugv = static_cast<std::uint32_t>(std::max(p.to_ugv, 0));
    w.initial_point_m = to_msg(p.initial_point_m);
    w.transition_point_m = to_msg(p.transition_point_m);
    w.final_point_m = to_msg(p.final_point_m);
    w.final_action = to_msg(p.final_action);
    w.vmax_m_s = p.vmax_m_s;
    w.amax_m_s2 = p.amax_m_s2;
    w.method = p.method;
    m.processes.push_back(w);
  }
  return m;
}

namespace {
// A wire id beyond int's range must not wrap into a valid UGV: it becomes -1 (invalid).
int to_id(std::uint32_t id) {
  return id > static_cast<std::uint32_t>(std::numeric_limits<int>::max()) ? -1
                                                                          : static_cast<int>(id);
}
}  // namespace

mission::Task from_msg(const msg::TransitionTask& m) {
  mission::Task task;
  task.task_id = m.task_id;
  task.uav_id = to_id(m.uav_id);
  for (const msg::TransitionProcess& w : m.processes) {
    mission::TransitionProcess p;
    p.from_ugv = to_id(w.from_ugv);
    p.to_ugv = to_id(w.to_ugv);
    p.initial_point_m = to_eigen(w.initial_point_m);
    p.transition_point_m = to_eigen(w.transition_point_m);
    p.final_point_m = to_eigen(w.final_point_m);
    const auto action = from_msg(w.final_action);
    p.final_action = action.value_or(mission::FinalAction::None);
    if (!action) p.final_point_m.setConstant(std::numeric_limits<double>::quiet_NaN());
    p.vmax_m_s = w.vmax_m_s;
    p.amax_m_s2 = w.amax_m_s2;
    p.method = w.method;  // an unknown name is rejected by Task::validate
    task.processes.push_back(p);
  }
  return task;
}

}  // namespace cover::wire
