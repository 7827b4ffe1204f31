#pragma once

#include <cstdint>

namespace cover::firmware {

// Something the test saw, with when it saw it: the host's monotonic clock, ns
// (clock::monotonic_ns()), the clock every time the firmware tests compare is on.
template <typename T>
struct Timed {
  std::int64_t at_ns = 0;
  T value{};
};

}  // namespace cover::firmware
