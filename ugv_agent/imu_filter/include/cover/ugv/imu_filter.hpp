#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>

#include "cover/config/param_fields.hpp"
#include "cover/vocabulary/ugv_imu.hpp"

namespace cover::ugv {

// Cut-offs and sanity limits of the UGV IMU pre-processing. The paper applies "a
// first-order low-pass filter" to the UGV IMU without giving the cut-off; these are
// our choices (documented in config/ugv_agent.yaml, section ugv_agent.imu_filter: the one
// source of truth for the agent and for the simulator's in-process filter).
struct ImuFilterParams {
  // Low-pass cut-off for the specific force (accelerometer), Hz. 15 Hz keeps the lag
  // (~10 ms) well below the 100 Hz MPC period while removing motor/ground vibration.
  double specific_force_cutoff_hz = 15.0;
  // Low-pass cut-off for the angular velocity (gyro), Hz.
  double angular_velocity_cutoff_hz = 15.0;
  // Second low-pass on the differentiated (filtered) gyro, Hz: differentiation
  // amplifies noise by 1/dt, so the angular acceleration needs a much lower cut-off. The
  // model extrapolates Omega with it over the 2 s horizon and multiplies it by the distance
  // to the UGV (beta x p), so its noise is the command's: at 5 Hz the simulated gyro's
  // 0.005 rad/s noise made every method's body-rate and thrust steps at the frame switch
  // about twice what they are at 1 Hz (docs/benchmarks.md, Fig. 8), while a UGV's angular
  // acceleration changes over seconds (a 0.16 s lag).
  double angular_acceleration_cutoff_hz = 1.0;
  // A gap between samples longer than this restarts the filter from the new sample:
  // blending across a long outage would output stale dynamics.
  double max_sample_gap_s = 0.1;
  // Samples beyond these magnitudes are rejected as sensor faults (16 g, 2000 deg/s:
  // the full-scale ranges of common MEMS IMUs).
  double max_specific_force_m_s2 = 160.0;
  double max_angular_velocity_rad_s = 35.0;

  // Each field once (config/param_fields.hpp): load, validate, the shipped-file test and
  // the documentation walk this list.
  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using cover::config::Field;
    visit("specific_force_cutoff_hz", self.specific_force_cutoff_hz,
          Field("Hz", "first-order low-pass cut-off on the specific force").above(0.0));
    visit("angular_velocity_cutoff_hz", self.angular_velocity_cutoff_hz,
          Field("Hz", "first-order low-pass cut-off on the gyro").above(0.0));
    visit("angular_acceleration_cutoff_hz", self.angular_acceleration_cutoff_hz,
          Field("Hz", "low-pass cut-off on the differentiated gyro").above(0.0));
    visit("max_sample_gap_s", self.max_sample_gap_s,
          Field("s", "a longer gap between samples restarts the filter").above(0.0));
    visit("max_specific_force_m_s2", self.max_specific_force_m_s2,
          Field("m/s^2", "samples above this magnitude are rejected").above(0.0));
    visit("max_angular_velocity_rad_s", self.max_angular_velocity_rad_s,
          Field("rad/s", "gyro samples above this magnitude are rejected").above(0.0));
  }

  static ImuFilterParams load(cover::config::YamlReader& reader);
  // Reads section `ugv_agent` -> `imu_filter` of an agent configuration file (the other
  // keys of `ugv_agent` belong to the agent, which checks them).
  static ImuFilterParams load_file(const std::string& path);
  // config/ugv_agent.yaml of the shipped configuration.
  static ImuFilterParams load_default();
  // Throws cover::config::ConfigError naming the bad key; `context` prefixes the message.
  void validate(const std::string& context = "imu_filter") const;
};

enum class ImuFilterStatus : std::uint8_t {
  Updated,             // sample accepted and blended in
  Started,             // first sample: outputs seeded with it, angular acceleration zero
  RestartedAfterGap,   // gap > max_sample_gap_s: restarted from this sample
  RejectedNonFinite,   // NaN/Inf in the sample or its stamp: last output kept
  RejectedOutOfRange,  // magnitude beyond the sensor's full scale: last output kept
  RejectedStaleStamp,  // stamp not after the previous one (dt <= 0): last output kept
};

const char* to_string(ImuFilterStatus status);
inline bool accepted(ImuFilterStatus s) {
  return s == ImuFilterStatus::Updated || s == ImuFilterStatus::Started ||
         s == ImuFilterStatus::RestartedAfterGap;
}

// First-order low-pass on specific force and gyro, plus a filtered derivative of the
// filtered gyro for the angular acceleration. Discretised exactly for the measured dt
// (alpha = 1 - exp(-dt / tau)), so jittery sample times do not change the cut-off.
// Never throws; bad samples are rejected with a status and the last good output stays.
class ImuFilter {
 public:
  // `params` must have passed validate() (done by load()).
  explicit ImuFilter(const ImuFilterParams& params = {});

  ImuFilterStatus update(const ImuSample& sample);
  void reset();

  bool has_output() const { return started_; }
  const FilteredImu& output() const { return output_; }
  const ImuFilterParams& params() const { return params_; }

 private:
  bool is_plausible(const ImuSample& sample) const;
  void start_from(const ImuSample& sample);

  ImuFilterParams params_;
  double specific_force_tau_s_;
  double angular_velocity_tau_s_;
  double angular_acceleration_tau_s_;
  bool started_ = false;
  FilteredImu output_;
};

}  // namespace cover::ugv
