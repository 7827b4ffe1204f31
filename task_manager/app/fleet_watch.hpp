#pragma once

#include <mutex>
#include <string>
#include <vector>

#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/task_manager/live_view.hpp"
#include "fleet_intake.hpp"

namespace cover::task_manager {

// What the manager hears of the fleet: each UAV agent's heartbeat (cover/uav/<u>/status)
// and task status (cover/task/status), each UGV's IMU (cover/ugv/<k>/imu), each UAV's
// autopilot where a flight-controller bridge reports it (cover/uav/<u>/fc), stamped with
// the host's wall clock when they arrive, through FleetIntake's checks (refused samples
// are counted and logged, at most once per reason per log period). Thread-safe: receive
// threads write, the manager thread takes a LiveView.
class FleetWatch {
 public:
  FleetWatch(dds::Participant& participant, int max_uavs, int max_ugvs,
             wire::IntakeLimits limits = {});
  LiveView view() const;
  wire::RejectionCounts rejections() const;

 private:
  void log_if(std::optional<wire::Rejection> why, const std::string& topic);  // mutex_ held

  mutable std::mutex mutex_;
  wire::IntakeLimits limits_;
  FleetIntake intake_;
  wire::RejectionCounts logged_;  // only its log clocks are used
  std::vector<dds::Reader<msg::UavStatus>> uav_readers_;
  std::vector<dds::Reader<msg::UgvImu>> ugv_readers_;
  std::vector<dds::Reader<msg::FcState>> fc_readers_;
  dds::Reader<msg::TaskStatus> task_reader_;
};

}  // namespace cover::task_manager
