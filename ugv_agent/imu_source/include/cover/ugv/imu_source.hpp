#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "cover/ugv/imu_filter.hpp"

namespace cover::ugv {

enum class ImuSourceState : std::uint8_t {
  Ok,     // delivering (or waiting for) samples
  Ended,  // a finite source (replay) delivered its last sample: a clean end
  Gone,   // the device (or the simulator) disappeared: no sample will come again
};
const char* to_string(ImuSourceState state);

struct ImuSourceStatus {
  ImuSourceState state = ImuSourceState::Ok;
  // Samples the device produced that this reader never saw (it fell behind the device's
  // buffer). Counted, not hidden: the filter restarts across the hole (max_sample_gap_s).
  std::uint64_t lost_samples = 0;
  std::string detail;  // why Ended / Gone, for the log
};

// A raw IMU device as the UGV agent sees it. read() is the blocking device read of a
// driver: it returns what arrived since the previous call, or nothing after `timeout`.
// One thread uses a source; implementations are not thread-safe.
class ImuSource {
 public:
  virtual ~ImuSource() = default;

  // Replaces `out` with the samples that arrived since the last call, oldest first (stamps
  // in s). Waits up to `timeout` when none are there yet. Returns out.size(): 0 on
  // timeout. The call that finds the source Ended or Gone may still return its last
  // samples; check status() after using them. Later calls return 0. Never throws.
  virtual std::size_t read(std::vector<ImuSample>& out, std::chrono::milliseconds timeout) = 0;

  // "sim-shm:<segment>", "csv:<file>": where the samples come from, for logs and status.
  virtual std::string describe() const = 0;
  virtual ImuSourceStatus status() const = 0;
};

}  // namespace cover::ugv
