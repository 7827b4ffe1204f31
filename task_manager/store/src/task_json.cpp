#include "cover/task_manager/task_json.hpp"

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "cover/task_manager/store_error.hpp"

namespace cover::task_manager {
namespace {
using nlohmann::json;

// JSON has no NaN or infinity, and a rejected task may carry them (that is why it was
// rejected): write them as strings rather than lose them to null.
json number_to_json(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0.0 ? "inf" : "-inf";
  return value;
}

double number_from_json(const json& value) {
  if (value.is_number()) return value.get<double>();
  if (value == "nan") return std::numeric_limits<double>::quiet_NaN();
  if (value == "inf") return std::numeric_limits<double>::infinity();
  if (value == "-inf") return -std::numeric_limits<double>::infinity();
  throw StoreError("task JSON: expected a number, got " + value.dump());
}

json point_to_json(const Eigen::Vector3d& point) {
  return json::array(
      {number_to_json(point.x()), number_to_json(point.y()), number_to_json(point.z())});
}

Eigen::Vector3d point_from_json(const json& value) {
  if (!value.is_array() || value.size() != 3) {
    throw StoreError("task JSON: expected a point [x, y, z], got " + value.dump());
  }
  return {number_from_json(value[0]), number_from_json(value[1]), number_from_json(value[2])};
}

mission::FinalAction action_from_json(const json& value) {
  for (const auto action :
       {mission::FinalAction::None, mission::FinalAction::Land, mission::FinalAction::Deliver}) {
    if (value == mission::to_string(action)) return action;
  }
  throw StoreError("task JSON: final_action " + value.dump() + " is not none | land | deliver");
}

json process_to_json(const mission::TransitionProcess& p) {
  return json{{"from_ugv", p.from_ugv},
              {"to_ugv", p.to_ugv},
              {"initial_point_m", point_to_json(p.initial_point_m)},
              {"transition_point_m", point_to_json(p.transition_point_m)},
              {"final_point_m", point_to_json(p.final_point_m)},
              {"final_action", mission::to_string(p.final_action)},
              {"vmax_m_s", number_to_json(p.vmax_m_s)},
              {"amax_m_s2", number_to_json(p.amax_m_s2)},
              {"method", p.method}};
}

mission::TransitionProcess process_from_json(const json& j) {
  mission::TransitionProcess p;
  p.from_ugv = j.at("from_ugv").get<int>();
  p.to_ugv = j.at("to_ugv").get<int>();
  p.initial_point_m = point_from_json(j.at("initial_point_m"));
  p.transition_point_m = point_from_json(j.at("transition_point_m"));
  p.final_point_m = point_from_json(j.at("final_point_m"));
  p.final_action = action_from_json(j.at("final_action"));
  p.vmax_m_s = number_from_json(j.at("vmax_m_s"));
  p.amax_m_s2 = number_from_json(j.at("amax_m_s2"));
  // Absent in tasks stored before processes carried a method: the UAV's own.
  p.method = j.value("method", std::string());
  return p;
}
}  // namespace

std::string task_to_json(const mission::Task& task) {
  json processes = json::array();
  for (const auto& p : task.processes) processes.push_back(process_to_json(p));
  // A string from the wire need not be UTF-8 (such a method is rejected, but recorded):
  // invalid bytes are stored as U+FFFD rather than failing the submission.
  return json{{"task_id", task.task_id}, {"uav_id", task.uav_id}, {"processes", processes}}.dump(
      -1, ' ', false, json::error_handler_t::replace);
}

mission::Task task_from_json(const std::string& text) {
  try {
    const json j = json::parse(text);
    mission::Task task;
    task.task_id = j.at("task_id").get<std::string>();
    task.uav_id = j.at("uav_id").get<int>();
    const json& processes = j.at("processes");
    if (!processes.is_array()) throw StoreError("task JSON: processes is not a list");
    for (const json& p : processes) task.processes.push_back(process_from_json(p));
    return task;
  } catch (const json::exception& e) {
    throw StoreError(std::string("task JSON: ") + e.what());
  }
}

}  // namespace cover::task_manager
