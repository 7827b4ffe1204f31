#pragma once

#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/task_manager/live_view.hpp"

namespace cover::task_manager {

// What the manager hears of the fleet: each UAV agent's heartbeat (cover/uav/<u>/status)
// and task status (cover/task/status), each UGV's IMU (cover/ugv/<k>/imu), stamped with
// the host's wall clock when they arrive. Thread-safe: receive threads write, the manager
// thread takes a LiveView.
class FleetWatch {
 public:
  FleetWatch(dds::Participant& participant, int max_uavs, int max_ugvs);
  LiveView view() const;

 private:
  void on_uav_status(const msg::UavStatus& status);
  void on_task_status(const msg::TaskStatus& status);
  void on_ugv_imu(const msg::UgvImu& imu);

  mutable std::mutex mutex_;
  LiveView view_;
  std::map<std::string, std::string> task_messages_;  // the agents' last word per task id
  std::vector<dds::Reader<msg::UavStatus>> uav_readers_;
  std::vector<dds::Reader<msg::UgvImu>> ugv_readers_;
  dds::Reader<msg::TaskStatus> task_reader_;
};

}  // namespace cover::task_manager
