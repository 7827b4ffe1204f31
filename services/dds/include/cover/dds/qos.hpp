#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace cover::dds {

enum class Reliability { BestEffort, Reliable };
enum class Durability { Volatile, TransientLocal };

// The QoS of one topic, applied identically to its writers and readers. Every policy is
// set explicitly because the two vendors' defaults differ (see docs/topics.md).
struct QosProfile {
  std::string name;
  Reliability reliability = Reliability::BestEffort;
  Durability durability = Durability::Volatile;
  int history_depth = 1;    // keep-last depth per instance
  double deadline_s = 0.0;  // expected max period between samples; 0 = no deadline
  // Instances (distinct keys) a writer or reader keeps; set on both vendors because Fast
  // DDS defaults to 10, which silently refuses the 11th task's status.
  int max_instances = 4096;
  // Reliable readers: how long a reader waits after a writer's heartbeat before it
  // acknowledges (one acknowledgement then covers every sample since); 0 = the vendor's
  // default (Fast DDS 5 ms). Fast DDS only: Cyclone acknowledges by its own settings.
  double acknowledgement_delay_s = 0.0;

  void validate() const;  // throws DdsError with the reason
};

// Named profiles:
//  sensor  : best-effort, volatile, keep-last 1, deadline 50 ms (IMU, relative states);
//  command : reliable, volatile, keep-last 1, deadline 50 ms (UAV commands: the newest
//            wins, but an arm/disarm or release is not dropped by one lost packet);
//  state   : reliable, transient-local, keep-last 8 (tasks, task and UAV status,
//            references: a late joiner gets the latest);
//  request : reliable, volatile, keep-last 64 (requests to the task manager and its
//            replies: a burst from several stations is queued, none overwritten);
//  exchange: best-effort, volatile, keep-last 64 (the clock exchange: a lost request or
//            reply is a lost sample, as NTP's over UDP; reliable, every one of a fleet's
//            askers and answerers would heartbeat and acknowledge every other).
QosProfile sensor_qos();
QosProfile command_qos();
QosProfile state_qos();
QosProfile request_qos();
QosProfile exchange_qos();

// Looks a profile up by name; throws DdsError listing the known names.
QosProfile qos_profile(std::string_view name);
std::vector<std::string> qos_profile_names();

}  // namespace cover::dds
