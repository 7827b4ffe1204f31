#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "cover/ugv/imu_filter.hpp"
#include "cover/ugv/imu_health.hpp"
#include "cover/ugv/imu_source.hpp"
#include "cover/ugv/ugv_sensor_pipeline.hpp"
#include "imu_publisher.hpp"
#include "ugv_agent_params.hpp"

namespace cover::ugv {

// Exit codes of cover-ugv-agent (documented in ugv_agent/README.md).
inline constexpr int kExitOk = 0;
inline constexpr int kExitUsage = 2;
inline constexpr int kExitSourceFailed = 3;

// The agent's loop: read the source, run every sample through the UGV pipeline (filter,
// speed estimate), publish the accepted ones, keep the health and the heartbeat. Runs until
// shutdown is requested or the source ends.
class UgvAgent {
 public:
  UgvAgent(const UgvAgentParams& params, std::unique_ptr<ImuSource> source,
           ImuPublisher& publisher);

  // kExitOk on shutdown or a source that ended, kExitSourceFailed when it went away.
  int run();

 private:
  // At most one log line per second for a repeated event, with the count since the last.
  struct RateLimitedLog {
    std::int64_t last_ns = INT64_MIN / 2;
    std::uint64_t pending = 0;
  };

  void handle(const ImuSample& sample, std::int64_t now_ns);
  void log_rejection(ImuFilterStatus status, std::int64_t now_ns);
  void log_odometry_rejection(SpeedSampleStatus status, std::int64_t now_ns);
  void log_speed_source(const SpeedEstimate& speed);
  void log_lost_samples(std::uint64_t lost_total, std::int64_t now_ns);
  void update_health(std::int64_t now_ns);
  void publish_status();
  int finish(const ImuSourceStatus& status);

  UgvAgentParams params_;
  std::unique_ptr<ImuSource> source_;
  ImuPublisher& publisher_;
  UgvSensorPipeline pipeline_;
  ImuHealthMonitor health_monitor_;
  ImuHealth health_;
  std::string source_name_;
  std::vector<ImuSample> batch_;
  double last_stamp_s_ = 0.0;
  std::uint32_t accepted_ = 0;
  std::uint32_t rejected_ = 0;
  std::uint64_t lost_reported_ = 0;
  std::int64_t next_status_ns_ = 0;
  std::int64_t last_publish_ns_ = 0;  // when an IMU sample last went out (monotonic)
  RateLimitedLog rejections_log_;
  RateLimitedLog odometry_log_;
  std::uint32_t odometry_rejected_ = 0;
  model::SpeedSource logged_speed_source_ = model::SpeedSource::None;
  RateLimitedLog lost_log_;
};

}  // namespace cover::ugv
