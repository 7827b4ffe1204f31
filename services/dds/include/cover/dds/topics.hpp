#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include "cover/dds/qos.hpp"
#include "cover/dds/topic.hpp"
#include "cover/dds/topic_descriptor.hpp"
#include "cover/msg/types.hpp"

namespace cover::dds {
namespace topics {

// The topic catalogue: one row per topic, and nothing about a topic is defined elsewhere.
// A new topic adds its type to idl/cover_msgs.idl, a row here and an accessor below, and
// its line in docs/topics.md (`cover topics --markdown` prints it; a test compares).
// Each message type has exactly one topic: accessors find their row by type.
inline constexpr std::tuple kCatalog{
    TopicDescriptor<msg::UgvImu, UgvId>{"cover/ugv/<k>/imu", &sensor_qos, "200 Hz",
                                        "ugv_agent k (or sim) -> uav_agent",
                                        "UGV k's filtered IMU in G_k"},
    TopicDescriptor<msg::RelativeState, UavId, UgvId>{
        "cover/uav/<u>/rel/<k>", &sensor_qos, "100 Hz",
        "relative localisation (or sim) -> uav_agent", "UAV u's state relative to UGV k, in G_k"},
    TopicDescriptor<msg::UavCommand, UavId>{"cover/uav/<u>/cmd", &command_qos, "100 Hz",
                                            "uav_agent -> flight controller (or sim)",
                                            "thrust and body-rate command to UAV u"},
    TopicDescriptor<msg::UavStatus, UavId>{
        "cover/uav/<u>/status", &state_qos, "10 Hz", "uav_agent -> ground station",
        "stage, reference frame, solver and failsafe state of UAV u"},
    TopicDescriptor<msg::ControlTrace, UavId>{
        "cover/uav/<u>/trace", &command_qos, "100 Hz", "uav_agent -> flight log, sim (metrics)",
        "per control step: stage, failsafe, solver, reference point of UAV u"},
    TopicDescriptor<msg::UgvStatus, UgvId>{"cover/ugv/<k>/status", &state_qos, "1 Hz",
                                           "ugv_agent k -> ground station",
                                           "UGV k's agent heartbeat: IMU source, rate, health"},
    TopicDescriptor<msg::SimClock>{"cover/sim/clock", &command_qos, "100 Hz",
                                   "sim -> agents (lockstep tick)",
                                   "the simulator's time, one sample per control period"},
    TopicDescriptor<msg::ReferenceTrajectory, UavId>{
        "cover/uav/<u>/reference", &state_qos, "per stage", "uav_agent -> ground station",
        "sampled reference of the current stage, for display"},
    // Volatile: a UAV agent that (re)starts must not receive, and fly, old tasks.
    TopicDescriptor<msg::TransitionTask>{"cover/task/request", &request_qos, "on demand",
                                         "task_manager -> uav_agent",
                                         "task sequences dispatched to a UAV"},
    TopicDescriptor<msg::TaskAbort>{"cover/task/abort", &command_qos, "on demand",
                                    "task_manager, ground station -> uav_agent",
                                    "stop a UAV's running task: hold, then its safe action"},
    TopicDescriptor<msg::ManagerRequest>{"cover/manager/request", &request_qos, "on demand",
                                         "ground station -> task_manager",
                                         "submit, abort or query tasks"},
    TopicDescriptor<msg::ManagerReply>{"cover/manager/reply", &request_qos, "on demand",
                                       "task_manager -> ground station",
                                       "the answer to one request, by request id"},
    TopicDescriptor<msg::TaskStatus>{"cover/task/status", &state_qos, "on change",
                                     "uav_agent -> task_manager, ground station",
                                     "progress and outcome of each task"},
    TopicDescriptor<msg::FcState, UavId>{
        "cover/uav/<u>/fc", &state_qos, "10 Hz",
        "fc_bridge u -> uav_agent, task_manager, ground station",
        "UAV u's autopilot: link, mode, armed, landed state, battery, hover thrust"},
    TopicDescriptor<msg::FcRequest>{"cover/fc/request", &request_qos, "on demand",
                                    "ground station -> fc_bridge",
                                    "arm, disarm, offboard or land one UAV's autopilot"},
    TopicDescriptor<msg::FcReply>{"cover/fc/reply", &request_qos, "on demand",
                                  "fc_bridge -> ground station",
                                  "the autopilot's answer to one request, by request id"},
    TopicDescriptor<msg::TimeSyncRequest>{
        "cover/time/request", &exchange_qos, "1 Hz per asker",
        "uav_agent, ugv_agent, task_manager -> sim, agents, fc_bridge",
        "clock request (t1) of the four-timestamp offset exchange (docs/time.md)"},
    // One topic per asker: a reply reaches its asker only, not every asker of the fleet.
    TopicDescriptor<msg::TimeSyncReply, ProcessName>{
        "cover/time/reply/<process>", &exchange_qos, "on request",
        "sim, agents, fc_bridge -> the asking uav_agent, ugv_agent or task_manager",
        "a peer's receive (t2) and send (t3) times for one clock request of <process>"},
};

// The row of message type T, bound to `ids`; does not compile when T has no row or the
// row takes other ids.
template <typename T, typename... Ids>
Topic<T> bind(Ids... ids) {
  return std::get<TopicDescriptor<T, Ids...>>(kCatalog).bind(ids...);
}

inline Topic<msg::UgvImu> ugv_imu(std::uint32_t ugv) {
  return bind<msg::UgvImu>(UgvId{ugv});
}
inline Topic<msg::UgvStatus> ugv_status(std::uint32_t ugv) {
  return bind<msg::UgvStatus>(UgvId{ugv});
}
inline Topic<msg::RelativeState> relative_state(std::uint32_t uav, std::uint32_t ugv) {
  return bind<msg::RelativeState>(UavId{uav}, UgvId{ugv});
}
inline Topic<msg::UavCommand> uav_command(std::uint32_t uav) {
  return bind<msg::UavCommand>(UavId{uav});
}
inline Topic<msg::ControlTrace> uav_trace(std::uint32_t uav) {
  return bind<msg::ControlTrace>(UavId{uav});
}
inline Topic<msg::UavStatus> uav_status(std::uint32_t uav) {
  return bind<msg::UavStatus>(UavId{uav});
}
inline Topic<msg::ReferenceTrajectory> uav_reference(std::uint32_t uav) {
  return bind<msg::ReferenceTrajectory>(UavId{uav});
}
inline Topic<msg::TransitionTask> task_request() {
  return bind<msg::TransitionTask>();
}
inline Topic<msg::TaskStatus> task_status() {
  return bind<msg::TaskStatus>();
}
inline Topic<msg::TaskAbort> task_abort() {
  return bind<msg::TaskAbort>();
}
inline Topic<msg::ManagerRequest> manager_request() {
  return bind<msg::ManagerRequest>();
}
inline Topic<msg::ManagerReply> manager_reply() {
  return bind<msg::ManagerReply>();
}
inline Topic<msg::SimClock> sim_clock() {
  return bind<msg::SimClock>();
}
inline Topic<msg::FcState> fc_state(std::uint32_t uav) {
  return bind<msg::FcState>(UavId{uav});
}
inline Topic<msg::FcRequest> fc_request() {
  return bind<msg::FcRequest>();
}
inline Topic<msg::FcReply> fc_reply() {
  return bind<msg::FcReply>();
}
inline Topic<msg::TimeSyncRequest> time_request() {
  return bind<msg::TimeSyncRequest>();
}
// The replies to the clock requests of process `asker` ("cover-uav-agent-0"); throws
// DdsError when `asker` is not a valid_process_name.
Topic<msg::TimeSyncReply> time_reply(const std::string& asker);

// The processes of a fleet that ask clocks (docs/time.md), whose reply topics a recorder
// or a permissions file names: the task manager, every UAV agent and every UGV agent.
std::vector<std::string> clock_askers(std::uint32_t uavs, std::uint32_t ugvs);

}  // namespace topics

// The catalogue as data, for tools that work by name (`cover topics`, echo, pub) and for
// the docs check; built from topics::kCatalog, in its order.
struct TopicInfo {
  std::string pattern;    // <k>: UGV id, <u>: UAV id, <process>: a process name
  std::string type_name;  // scoped IDL name (T::kTypeName), e.g. "cover::idl::UgvImu"
  std::string qos_profile;
  std::string rate;
  std::string flow;  // "publisher -> subscribers"
  std::string description;
};

const std::vector<TopicInfo>& topic_catalog();

// The catalogue entry a concrete topic name belongs to, or nullptr (<k> and <u> match
// decimal ids, <process> a valid_process_name).
const TopicInfo* find_topic(std::string_view topic_name);

// The entry of `name`; throws DdsError when `name` is not catalogued or its type is not
// `type_name` (the message names both types).
const TopicInfo& require_catalogued(std::string_view name, std::string_view type_name);

// A catalogued topic looked up by its concrete name at run time (the `cover` CLI's echo
// and pub); throws DdsError when the name is not catalogued or its type is not T.
template <typename T>
Topic<T> catalogued_topic(std::string_view name) {
  const TopicInfo& info = require_catalogued(name, T::kTypeName);
  return Topic<T>(std::string(name), qos_profile(info.qos_profile), true);
}

}  // namespace cover::dds
