#pragma once

#include <cstddef>
#include <cstdint>

#include "cover/firmware/firmware_rig.hpp"

namespace cover::firmware {

// When the bridge's hover-thrust estimate counts as settled, so that a hover on thrust g can
// begin: over the last `window_ns` it moved by no more than `spread` of itself (an error of
// 1 % is 0.1 m/s^2 of vertical acceleration on thrust g), at least `after_take_off_ns` after
// the take-off (the climb's thrust excites the estimate), with the firmware's vertical speed
// below `max_vz_m_s` (a hover on thrust g has nothing that brings a speed it starts with
// back). The bridge publishes its state at 10 Hz: the window must hold `min_states` of them.
struct HoverSettleRule {
  std::int64_t window_ns = 2'000'000'000;
  double spread = 0.01;
  std::size_t min_states = 10;
  std::int64_t after_take_off_ns = 8'000'000'000;
  double max_vz_m_s = 0.05;
};

// `now_ns` and `airborne_ns` on clock::monotonic_ns, as the rig stamps what it hears.
bool hover_estimate_settled(FirmwareRig& rig, std::int64_t airborne_ns, std::int64_t now_ns,
                            const HoverSettleRule& rule = {});

}  // namespace cover::firmware
