#include "imu_publisher.hpp"

#include "cover/dds/topics.hpp"
#include "cover/wire/eigen.hpp"
#include "cover/wire/sensors.hpp"

namespace cover::ugv {

ImuPublisher::ImuPublisher(cover::dds::Participant& participant, std::uint32_t ugv_id)
    : ugv_id_(ugv_id),
      imu_writer_(participant.make_writer(cover::dds::topics::ugv_imu(ugv_id))),
      status_writer_(participant.make_writer(cover::dds::topics::ugv_status(ugv_id))) {}

void ImuPublisher::publish_imu(const FilteredImu& imu, const SpeedEstimate& speed) {
  last_ = cover::wire::to_msg(imu, speed, ugv_id_, seq_++);
  imu_writer_.write(*last_);
}

void ImuPublisher::republish_last() {
  if (last_) imu_writer_.write(*last_);
}

void ImuPublisher::publish_status(const UgvStatusReport& report) {
  cover::msg::UgvStatus m;
  m.ugv_id = ugv_id_;
  m.stamp_ns = cover::wire::to_stamp_ns(report.stamp_s);
  m.source = report.source;
  m.imu_rate_hz = report.imu_rate_hz;
  m.healthy = report.healthy;
  m.samples = report.samples;
  m.rejected_samples = report.rejected_samples;
  status_writer_.write(m);
}

void ImuPublisher::flush_status(std::chrono::milliseconds timeout) {
  status_writer_.wait_for_acknowledgments(timeout);
}

}  // namespace cover::ugv
