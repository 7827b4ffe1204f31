#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

#include "cover/dds/participant.hpp"
#include "cover/msg/types.hpp"
#include "cover/ugv/imu_filter.hpp"
#include "cover/ugv/speed_estimator.hpp"

namespace cover::ugv {

// What cover/ugv/<k>/status says (see UgvStatus in idl/cover_msgs.idl).
struct UgvStatusReport {
  double stamp_s = 0.0;  // the newest sample's stamp: the IMU topic's time base
  std::string source;
  double imu_rate_hz = 0.0;
  bool healthy = false;
  std::uint32_t samples = 0;
  std::uint32_t rejected_samples = 0;
};

// The DDS side of the agent: UGV k's two topics. Everything else of the agent is DDS-free.
class ImuPublisher {
 public:
  ImuPublisher(cover::dds::Participant& participant, std::uint32_t ugv_id);

  // seq counts the published samples from 0, so a reader sees what it missed.
  void publish_imu(const FilteredImu& imu, const SpeedEstimate& speed);
  // The last sample again, same seq and stamp (nothing new from the device): the IMU
  // topic is best-effort, and a reader that matched just after a sample was sent, or
  // lost it, would otherwise wait for the next one. Readers judge age by the stamp.
  void republish_last();
  void publish_status(const UgvStatusReport& report);
  // Before exiting: lets the last (reliable) status reach its readers.
  void flush_status(std::chrono::milliseconds timeout);

 private:
  std::uint32_t ugv_id_;
  std::uint32_t seq_ = 0;
  std::optional<cover::msg::UgvImu> last_;
  cover::dds::Writer<cover::msg::UgvImu> imu_writer_;
  cover::dds::Writer<cover::msg::UgvStatus> status_writer_;
};

}  // namespace cover::ugv
