#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>

namespace cover::ugv {

struct ImuHealth {
  double imu_rate_hz = 0.0;  // raw samples that arrived in the last window, per second
  bool healthy = false;
};

// Is the IMU stream good enough to fly on? Healthy when, over the last second of host
// time, samples arrived at >= 80 % of the nominal rate and the filter accepted >= 80 % of
// them. Host time (arrival), not sample stamps: a stalled device must turn unhealthy even
// though its last stamps looked regular.
class ImuHealthMonitor {
 public:
  static constexpr double kMinFraction = 0.8;
  static constexpr std::int64_t kWindowNs = 1'000'000'000;

  explicit ImuHealthMonitor(double nominal_rate_hz) : nominal_rate_hz_(nominal_rate_hz) {}

  // `arrival_ns`: monotonic host time; calls in non-decreasing time order.
  void on_sample(std::int64_t arrival_ns, bool accepted);
  ImuHealth evaluate(std::int64_t now_ns);

 private:
  struct Arrival {
    std::int64_t time_ns;
    bool accepted;
  };

  double nominal_rate_hz_;
  std::deque<Arrival> window_;
  std::size_t accepted_in_window_ = 0;
};

}  // namespace cover::ugv
