#include "cover/mission/failsafe_ladder_hover_thrust.hpp"

#include <algorithm>
#include <cmath>

#include "cover/vocabulary/state.hpp"

namespace cover::mission {

void HoverThrustEstimate::clear() {
  head_ = 0;
  count_ = 0;
  thrust_sum_ = 0.0;
  valid_ = false;
}

void HoverThrustEstimate::add(double now_s, double height_m, double vertical_speed_m_s,
                              double thrust_up_m_s2, double period_s) {
  const bool usable = std::isfinite(now_s) && std::isfinite(height_m) &&
                      std::isfinite(vertical_speed_m_s) && std::isfinite(thrust_up_m_s2) &&
                      height_m >= kOnDeck_m && thrust_up_m_s2 > 0.0;
  if (!usable) {
    clear();
    return;
  }
  if (count_ > 0) {
    Sample& newest = ring_[(head_ + count_ - 1) % kCapacity];
    const double dt_s = now_s - newest.t_s;
    // A missed step or a clock jump breaks the window: the model needs consecutive steps.
    if (!(dt_s > 0.0) || dt_s > 3.0 * period_s) {
      clear();
    } else {
      thrust_sum_ += newest.thrust_up_m_s2 * dt_s;
    }
  }
  if (count_ == kCapacity) clear();
  ring_[(head_ + count_) % kCapacity] = {now_s, vertical_speed_m_s, thrust_up_m_s2};
  ++count_;
  // Drop the oldest while the rest still spans the window.
  while (count_ >= 3 && now_s - ring_[(head_ + 1) % kCapacity].t_s >= kWindow_s) {
    const Sample& oldest = ring_[head_];
    thrust_sum_ -= oldest.thrust_up_m_s2 * (ring_[(head_ + 1) % kCapacity].t_s - oldest.t_s);
    head_ = (head_ + 1) % kCapacity;
    --count_;
  }
  const Sample& oldest = ring_[head_];
  const double span_s = now_s - oldest.t_s;
  if (span_s < kMinWindow_s) return;
  const double accel_m_s2 = (vertical_speed_m_s - oldest.vz_m_s) / span_s;
  const double value = model::kGravity_m_s2 * (thrust_sum_ / span_s) /
                       std::max(model::kGravity_m_s2 + accel_m_s2, 0.5 * model::kGravity_m_s2);
  valid_ = std::isfinite(value);
  if (valid_) value_m_s2_ = value;
}

}  // namespace cover::mission
