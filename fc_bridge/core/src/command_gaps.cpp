#include "cover/fc_bridge/command_gaps.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace cover::fc_bridge {

void CommandGaps::add(double gap_s) {
  if (!std::isfinite(gap_s) || gap_s < 0.0) return;
  const auto bin = static_cast<std::size_t>(std::min(gap_s * 1e3, static_cast<double>(kBins - 1)));
  ++bins_[bin];
  ++count_;
  max_s_ = std::max(max_s_, gap_s);
}

double CommandGaps::quantile_s(double fraction) const {
  if (count_ == 0) return 0.0;
  const double wanted = std::clamp(fraction, 0.0, 1.0) * static_cast<double>(count_);
  std::uint64_t seen = 0;
  for (std::size_t bin = 0; bin < kBins; ++bin) {
    seen += bins_[bin];
    if (static_cast<double>(seen) >= wanted) return std::min((bin + 1) * 1e-3, max_s_);
  }
  return max_s_;
}

std::uint64_t CommandGaps::above(double limit_s) const {
  const auto first = static_cast<std::size_t>(std::max(0.0, std::floor(limit_s * 1e3)) + 1);
  std::uint64_t n = 0;
  for (std::size_t bin = std::min(first, kBins); bin < kBins; ++bin) n += bins_[bin];
  return n;
}

std::string CommandGaps::summary(double limit_s) const {
  char text[200];
  std::snprintf(text, sizeof text,
                "%llu gaps between agent commands: median %.0f ms, p99 %.0f ms, p99.9 %.0f ms, "
                "max %.0f ms, %llu over the %.0f ms timeout",
                static_cast<unsigned long long>(count_), quantile_s(0.5) * 1e3,
                quantile_s(0.99) * 1e3, quantile_s(0.999) * 1e3, max_s_ * 1e3,
                static_cast<unsigned long long>(above(limit_s)), limit_s * 1e3);
  return text;
}

}  // namespace cover::fc_bridge
