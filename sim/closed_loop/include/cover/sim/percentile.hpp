#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace cover::sim {

// The `fraction` quantile (0.5: median, 0.99: p99, 1: max) of `values`, by the rank
// below; NaN for an empty set (not measured, never a 0 that reads as a result). Takes a
// copy because it reorders. Every run metric (controller timing, sensor-to-command
// latency) uses this one.
inline double percentile(std::vector<double> values, double fraction) {
  if (values.empty()) return std::nan("");
  const auto index = static_cast<std::size_t>(fraction * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(index),
                   values.end());
  return values[index];
}

}  // namespace cover::sim
