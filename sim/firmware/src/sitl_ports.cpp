#include "cover/firmware/sitl_ports.hpp"

namespace cover::firmware {

std::vector<PortUse> ports_of(Autopilot firmware, int instance) {
  if (firmware == Autopilot::Px4) {
    return {{false, companion_port(instance)}, {false, px4_onboard_port(instance)},
            {false, px4_gcs_port(instance)},   {false, 14280 + instance},  // payload link
            {false, 13030 + instance},                                     // gimbal link
            {false, 19450 + instance}};                                    // SIH display link
  }
  const int base = 10 * instance;
  return {{false, companion_port(instance)},
          {true, arducopter_gcs_port(instance)},
          {true, 5762 + base},   // SERIAL1's default, were it not UDP
          {true, 5763 + base},   // SERIAL2
          {false, 5501 + base},  // RC input
          {false, physics_port(firmware, instance)}};
}

}  // namespace cover::firmware
