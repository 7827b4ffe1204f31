#include "cover/ugv/ugv_sensor_pipeline.hpp"

namespace cover::ugv {

UgvSensorPipeline::UgvSensorPipeline(const ImuFilterParams& filter_params,
                                     const SpeedEstimatorParams& speed_params)
    : filter_(filter_params), speed_(speed_params) {}

UgvSensorResult UgvSensorPipeline::update(const ImuSample& sample) {
  UgvSensorResult result;
  if (sample.wheel_speed_m_s) {
    result.odometry_status = speed_.update_odometry({sample.stamp_s, *sample.wheel_speed_m_s});
  }
  result.imu_status = filter_.update(sample);
  if (accepted(result.imu_status)) speed_.update_imu(filter_.output());
  return result;
}

}  // namespace cover::ugv
