#include "cover/firmware/hover_settle.hpp"

#include <algorithm>
#include <cmath>

namespace cover::firmware {

bool hover_estimate_settled(FirmwareRig& rig, std::int64_t airborne_ns, std::int64_t now_ns,
                            const HoverSettleRule& rule) {
  if (now_ns - airborne_ns < rule.after_take_off_ns) return false;
  const auto states = rig.states_since(now_ns - rule.window_ns);
  if (states.size() < rule.min_states) return false;
  double lo = 1.0, hi = 0.0;
  for (const auto& s : states) {
    lo = std::min(lo, s.value.hover_thrust);
    hi = std::max(hi, s.value.hover_thrust);
  }
  const auto position = rig.monitor().position();
  return hi - lo <= rule.spread * hi && position && std::abs(position->value.vz) < rule.max_vz_m_s;
}

}  // namespace cover::firmware
