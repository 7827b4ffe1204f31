#pragma once

#include <array>
#include <cstddef>

namespace cover::mission {

// The thrust that holds the UAV's height, learnt from the last second of nominal flight:
// under the ladder's model (vertical acceleration = g (thrust * up / hover - 1)) the mean
// thrust along up over a window and the window's change of vertical speed give it
// exactly, whatever the mass or a thrust bias. SAMPC's own estimate (the UGV's specific
// force minus its disturbance estimate) is used until a window of airborne flight exists:
// early in a flight it can be several percent off, which made a hover climb and a
// landing stall above its reference.
class HoverThrustEstimate {
 public:
  static constexpr double kWindow_s = 1.0;
  // Shorter spans already give it within ~1 % (mocap speed noise over the span): a fault
  // soon after take-off must not fall back on SAMPC's estimate.
  static constexpr double kMinWindow_s = 0.4;
  // A relative height below this is the deck (resting, the thrust holds nothing).
  static constexpr double kOnDeck_m = 0.1;

  void add(double now_s, double height_m, double vertical_speed_m_s, double thrust_up_m_s2,
           double period_s);
  bool valid() const { return valid_; }
  double value_m_s2() const { return value_m_s2_; }

 private:
  struct Sample {
    double t_s, vz_m_s, thrust_up_m_s2;
  };
  static constexpr std::size_t kCapacity = 256;
  void clear();
  std::array<Sample, kCapacity> ring_{};
  std::size_t head_ = 0;  // oldest
  std::size_t count_ = 0;
  double thrust_sum_ = 0.0;
  bool valid_ = false;
  double value_m_s2_ = 0.0;
};

}  // namespace cover::mission
