#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace cover::sim {

// The `fraction` quantile (0.5: median, 0.99: p99) of `values`, by the rank below; 0 for
// an empty set. Takes a copy because it reorders. Every run metric (controller timing,
// sensor-to-command latency) uses this one.
inline double percentile(std::vector<double> values, double fraction) {
  if (values.empty()) return 0.0;
  const auto index = static_cast<std::size_t>(fraction * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(index),
                   values.end());
  return values[index];
}

}  // namespace cover::sim
