#include "fleet_watch.hpp"

#include <spdlog/spdlog.h>

#include "cover/clock/clock.hpp"

namespace cover::task_manager {

FleetWatch::FleetWatch(dds::Participant& participant, int max_uavs, int max_ugvs,
                       wire::IntakeLimits limits)
    : limits_(limits), intake_(max_uavs, max_ugvs, limits) {
  for (int u = 0; u < max_uavs; ++u) {
    const auto topic = dds::topics::uav_status(static_cast<std::uint32_t>(u));
    uav_readers_.push_back(
        participant.make_reader(topic, [this, u, name = topic.name()](const msg::UavStatus& s) {
          const double now = clock::system_s();
          std::lock_guard<std::mutex> lock(mutex_);
          log_if(intake_.on_uav_status(s, u, now), name);
        }));
  }
  for (int u = 0; u < max_uavs; ++u) {
    const auto topic = dds::topics::fc_state(static_cast<std::uint32_t>(u));
    fc_readers_.push_back(
        participant.make_reader(topic, [this, u, name = topic.name()](const msg::FcState& s) {
          const double now = clock::system_s();
          std::lock_guard<std::mutex> lock(mutex_);
          log_if(intake_.on_fc_state(s, u, now), name);
        }));
  }
  for (int k = 0; k < max_ugvs; ++k) {
    const auto topic = dds::topics::ugv_imu(static_cast<std::uint32_t>(k));
    ugv_readers_.push_back(
        participant.make_reader(topic, [this, k, name = topic.name()](const msg::UgvImu& imu) {
          const double now = clock::system_s();
          std::lock_guard<std::mutex> lock(mutex_);
          log_if(intake_.on_ugv_imu(imu, k, now), name);
        }));
  }
  const auto status_topic = dds::topics::task_status();
  task_reader_ = participant.make_reader(
      status_topic, [this, name = status_topic.name()](const msg::TaskStatus& s) {
        std::lock_guard<std::mutex> lock(mutex_);
        log_if(intake_.on_task_status(s), name);
      });
}

void FleetWatch::log_if(std::optional<wire::Rejection> why, const std::string& topic) {
  if (!why || !logged_.log_due(*why, clock::monotonic_ns() * 1e-9, limits_.log_period_s)) return;
  spdlog::warn("dropped a sample on {}: {} (rejected so far: {})", topic, wire::to_string(*why),
               intake_.rejections().summary());
}

LiveView FleetWatch::view() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return intake_.view();
}

wire::RejectionCounts FleetWatch::rejections() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return intake_.rejections();
}

}  // namespace cover::task_manager
