#pragma once

#include "cover/ugv/imu_filter.hpp"
#include "cover/ugv/speed_estimator.hpp"

namespace cover::ugv {

// What one raw sample produced: the filter's verdict and outputs, and the speed estimate.
struct UgvSensorResult {
  ImuFilterStatus imu_status = ImuFilterStatus::Started;
  // Only meaningful when the sample carried a wheel speed.
  SpeedSampleStatus odometry_status = SpeedSampleStatus::Accepted;
};

// The UGV's per-sample processing, in one fixed order: the sample's wheel speed (when it
// carries one) into the speed estimator, the IMU into the filter, and the filter's output
// (when it accepted the sample) into the speed estimator. The UGV agent and the
// simulator's in-process harness both run this, so their outputs agree bit for bit.
class UgvSensorPipeline {
 public:
  UgvSensorPipeline(const ImuFilterParams& filter_params = {},
                    const SpeedEstimatorParams& speed_params = {});

  UgvSensorResult update(const ImuSample& sample);

  const ImuFilter& filter() const { return filter_; }
  const SpeedEstimator& speed() const { return speed_; }

 private:
  ImuFilter filter_;
  SpeedEstimator speed_;
};

}  // namespace cover::ugv
