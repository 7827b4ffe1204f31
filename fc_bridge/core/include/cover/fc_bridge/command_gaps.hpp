#pragma once

#include <array>
#include <cstdint>
#include <string>

namespace cover::fc_bridge {

// The gaps between the UAV agent's commands as the bridge received them: what decides the
// command timeout on a loaded companion (one late sample must not land the UAV). A 1 ms
// histogram up to 2 s, fixed size (recorded on the latency path, no allocation).
class CommandGaps {
 public:
  void add(double gap_s);
  std::uint64_t count() const { return count_; }
  double max_s() const { return max_s_; }
  // The gap that `fraction` of the gaps do not exceed (1 ms resolution); 0 when empty.
  double quantile_s(double fraction) const;
  // How many gaps exceeded `limit_s`.
  std::uint64_t above(double limit_s) const;
  // "12034 gaps: median 10 ms, p99 14 ms, p99.9 31 ms, max 87 ms, 0 over 100 ms".
  std::string summary(double limit_s) const;

 private:
  static constexpr std::size_t kBins = 2000;  // 1 ms each; the last holds everything longer
  std::array<std::uint32_t, kBins> bins_{};
  std::uint64_t count_ = 0;
  double max_s_ = 0.0;
};

}  // namespace cover::fc_bridge
