#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace cover::bench {

// The `fraction` quantile (0.5 = median, 0.99 = p99, 1.0 = max) of `values`, by nearest
// rank; NaN for an empty set (not measured: JSON null, never a 0 that reads as a result).
// Takes a copy because it reorders.
inline double percentile(std::vector<double> values, double fraction) {
  if (values.empty()) return std::nan("");
  std::sort(values.begin(), values.end());
  const auto index =
      static_cast<std::size_t>(fraction * static_cast<double>(values.size() - 1) + 0.5);
  return values[std::min(index, values.size() - 1)];
}

}  // namespace cover::bench
