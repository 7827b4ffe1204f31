#include "cover/fc_bridge/setpoint_stream.hpp"

#include <algorithm>

namespace cover::fc_bridge {

void SetpointStream::on_sent(double now_s) {
  if (last_s_ < 0.0 || now_s - last_s_ > kMaxGap_s) start_s_ = now_s;
  last_s_ = now_s;
  sent_s_[count_ % kHistory] = now_s;
  ++count_;
}

double SetpointStream::streaming_for_s(double now_s) const {
  if (last_s_ < 0.0 || now_s - last_s_ > kMaxGap_s) return 0.0;
  return now_s - start_s_;
}

double SetpointStream::rate_hz(double now_s) const {
  const std::size_t stored = std::min(count_, kHistory);
  std::size_t within = 0;
  for (std::size_t i = 0; i < stored; ++i) {
    const double t = sent_s_[(count_ - 1 - i) % kHistory];
    if (now_s - t > 1.0) break;  // newest first: the rest are older
    ++within;
  }
  return static_cast<double>(within);
}

}  // namespace cover::fc_bridge
