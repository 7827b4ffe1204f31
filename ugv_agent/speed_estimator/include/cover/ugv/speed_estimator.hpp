#pragma once

#include <cstdint>
#include <string>

#include "cover/config/param_fields.hpp"
#include "cover/ugv/imu_filter.hpp"
#include "cover/vocabulary/speed_estimate.hpp"
#include "cover/vocabulary/ugv_motion.hpp"

namespace cover::ugv {

// Parameters of the UGV forward speed estimate (config/ugv_agent.yaml, section
// ugv_agent.speed_estimator: the one source for the agent and the in-process harness).
struct SpeedEstimatorParams {
  // First-order low-pass on the wheel speed, Hz: removes encoder quantisation and
  // ground-induced noise while lagging the speed by ~1 / (2 pi f) = 32 ms.
  double odometry_cutoff_hz = 5.0;
  // Odometry older than this (at the latest IMU stamp) no longer counts, s: a wheel
  // speed from a stalled encoder driver must not be flown on.
  double odometry_timeout_s = 0.2;
  // |speed| beyond this is no ground vehicle's: odometry samples above it are rejected,
  // an IMU-derived estimate above it is not valid, m/s.
  double max_speed_m_s = 5.0;
  // The IMU speed u = a_y / yaw_rate is only formed while |yaw_rate| is at least this,
  // rad/s: the accelerometer noise and bias are divided by the yaw rate.
  double imu_min_yaw_rate_rad_s = 0.15;
  // Low-pass on a_y / yaw_rate, Hz (also the time constant of the spread below).
  double imu_speed_cutoff_hz = 0.5;
  // The vehicle must have turned (above imu_min_yaw_rate_rad_s, plausibly) for this long
  // before the IMU speed is valid, s: the low-pass and the spread settle meanwhile.
  double imu_settle_s = 1.0;
  // The exponentially weighted standard deviation of a_y / yaw_rate around its low-pass
  // must stay below this, m/s: a ratio that jumps (slip, bumps, low yaw rate) is not a
  // speed.
  double imu_max_spread_m_s = 0.25;

  // Each field once (config/param_fields.hpp): load, validate, the shipped-file test and
  // the documentation walk this list.
  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using cover::config::Field;
    visit("odometry_cutoff_hz", self.odometry_cutoff_hz,
          Field("Hz", "first-order low-pass on the wheel speed").above(0.0).at_most(1000.0));
    visit("odometry_timeout_s", self.odometry_timeout_s,
          Field("s", "older odometry is not used").above(0.0).at_most(10.0));
    visit("max_speed_m_s", self.max_speed_m_s,
          Field("m/s", "|speed| above this is no ground vehicle's").above(0.0).at_most(100.0));
    visit("imu_min_yaw_rate_rad_s", self.imu_min_yaw_rate_rad_s,
          Field("rad/s", "a_y / yaw_rate only while |yaw_rate| >= this").above(0.0).at_most(10.0));
    visit("imu_speed_cutoff_hz", self.imu_speed_cutoff_hz,
          Field("Hz", "low-pass on a_y / yaw_rate").above(0.0).at_most(100.0));
    visit(
        "imu_settle_s", self.imu_settle_s,
        Field("s", "turning this long before the IMU speed is valid").at_least(0.0).at_most(60.0));
    visit("imu_max_spread_m_s", self.imu_max_spread_m_s,
          Field("m/s", "the spread of a_y / yaw_rate must stay below this")
              .above(0.0)
              .at_most(100.0));
  }

  static SpeedEstimatorParams load(cover::config::YamlReader& reader);
  // Section `ugv_agent` -> `speed_estimator` of an agent configuration file.
  static SpeedEstimatorParams load_file(const std::string& path);
  // config/ugv_agent.yaml of the shipped configuration.
  static SpeedEstimatorParams load_default();
  // Throws cover::config::ConfigError naming the bad key; `context` prefixes the message.
  void validate(const std::string& context = "speed_estimator") const;
};

// One wheel odometry reading: the vehicle's signed forward speed (negative: reversing).
struct WheelOdometrySample {
  double stamp_s = 0.0;
  double speed_m_s = 0.0;
};

enum class SpeedSampleStatus : std::uint8_t {
  Accepted,
  RejectedNonFinite,   // NaN/Inf in the sample or its stamp: ignored
  RejectedOutOfRange,  // |speed| above max_speed_m_s: ignored
  RejectedStaleStamp,  // stamp not after the previous one of the same kind: ignored
};
const char* to_string(SpeedSampleStatus status);
// "none", "wheel odometry", "imu": for logs.
const char* to_string(model::SpeedSource source);

// The UGV's forward speed along its body x axis. Wheel odometry when fresh (low-passed);
// otherwise, for a ground vehicle without side slip, the lateral specific force is
// a_y = u * yaw_rate, so u = a_y / yaw_rate while the vehicle turns fast enough and the
// ratio is steady; driving straight with no odometry gives no estimate (source None).
// Reversing is reported as a negative speed. Never throws.
//
// Expected IMU-derived error (sim/include/cover/sim/imu_sensor.hpp's noise model): an
// accelerometer bias b_y gives a speed bias b_y / yaw_rate (0.02 m/s^2 at 0.5 rad/s:
// 0.04 m/s; at 0.25 rad/s: 0.08 m/s), a gyro bias b_z a relative error b_z / yaw_rate
// (0.002 rad/s: 0.4-0.8 %); the white noise, after the 15 Hz IMU filter and this 0.5 Hz
// low-pass, adds ~0.01 m/s at 0.25 rad/s. Measured in tests/ugv/speed_estimator_test.cpp.
class SpeedEstimator {
 public:
  // `params` must have passed validate() (done by load()).
  explicit SpeedEstimator(const SpeedEstimatorParams& params = {});

  SpeedSampleStatus update_odometry(const WheelOdometrySample& sample);
  // One filtered IMU output (after ImuFilter accepted a sample).
  SpeedSampleStatus update_imu(const FilteredImu& imu);
  void reset();

  const SpeedEstimate& estimate() const { return estimate_; }
  const SpeedEstimatorParams& params() const { return params_; }

 private:
  struct Lowpass {
    bool started = false;
    double stamp_s = 0.0;
    double value = 0.0;
  };
  // a_y / yaw_rate while turning: its low-pass, spread and when the turn began.
  struct ImuSpeed {
    bool turning = false;
    double since_s = 0.0;
    double stamp_s = 0.0;
    double mean_m_s = 0.0;
    double variance_m2_s2 = 0.0;
  };

  void update_imu_speed(double stamp_s, double ratio_m_s);
  bool imu_speed_valid(double now_s) const;
  void refresh(double now_s);

  SpeedEstimatorParams params_;
  double odometry_tau_s_;
  double imu_speed_tau_s_;
  Lowpass odometry_;
  bool imu_seen_ = false;
  double imu_stamp_s_ = 0.0;
  ImuSpeed imu_speed_;
  SpeedEstimate estimate_;
};

}  // namespace cover::ugv
