#include "cover/ugv/imu_health.hpp"

namespace cover::ugv {

void ImuHealthMonitor::on_sample(std::int64_t arrival_ns, bool accepted) {
  window_.push_back({arrival_ns, accepted});
  if (accepted) ++accepted_in_window_;
}

ImuHealth ImuHealthMonitor::evaluate(std::int64_t now_ns) {
  while (!window_.empty() && window_.front().time_ns <= now_ns - kWindowNs) {
    if (window_.front().accepted) --accepted_in_window_;
    window_.pop_front();
  }
  const double window_s = static_cast<double>(kWindowNs) * 1e-9;
  const auto arrived = static_cast<double>(window_.size());
  ImuHealth health;
  health.imu_rate_hz = arrived / window_s;
  health.healthy = health.imu_rate_hz >= kMinFraction * nominal_rate_hz_ &&
                   static_cast<double>(accepted_in_window_) >= kMinFraction * arrived;
  return health;
}

}  // namespace cover::ugv
