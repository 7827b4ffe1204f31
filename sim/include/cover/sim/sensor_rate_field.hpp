#pragma once

#include "cover/config/param_fields.hpp"

namespace cover::sim {

// A simulated sensor's `rate_hz`: the same bounds for every sensor (1 Hz to a 10 kHz
// sanity ceiling), the divisibility it needs in `doc`.
inline config::Field sensor_rate_field(const char* doc) {
  return config::Field("Hz", doc).at_least(1.0).at_most(10000.0);
}

}  // namespace cover::sim
