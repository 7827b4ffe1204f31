#pragma once

#include <array>
#include <cstddef>

namespace cover::fc_bridge {

// The setpoints sent, as the autopilot sees the stream: how long it has flowed without a
// gap (PX4 accepts OFFBOARD only after more than 2 Hz for about a second) and its rate.
class SetpointStream {
 public:
  // A gap longer than this breaks the stream: slower than 2 Hz.
  static constexpr double kMaxGap_s = 0.5;

  void on_sent(double now_s);
  // Seconds the stream has flowed without a gap, 0 when it is not flowing now.
  double streaming_for_s(double now_s) const;
  // Setpoints sent over the last second.
  double rate_hz(double now_s) const;
  double last_sent_s() const { return last_s_; }

 private:
  static constexpr std::size_t kHistory = 1024;  // > 1 s at the fastest sensible rate
  double start_s_ = -1.0;
  double last_s_ = -1.0;
  std::array<double, kHistory> sent_s_{};
  std::size_t count_ = 0;  // total sent; sent_s_ is a ring
};

}  // namespace cover::fc_bridge
