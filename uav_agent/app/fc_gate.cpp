#include "fc_gate.hpp"

#include <cstdio>

#include "cover/clock/clock.hpp"
#include "cover/wire/fc_state.hpp"

namespace cover::uav_agent {

FcGate::FcGate(dds::Participant& participant, std::uint32_t uav_id, bool required,
               double stale_after_s)
    : required_(required), stale_after_s_(stale_after_s) {
  reader_ = participant.make_reader(dds::topics::fc_state(uav_id), [this](const msg::FcState& s) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      latest_ = s;
      received_monotonic_ns_ = clock::monotonic_ns();
    }
    arrived_.notify_all();
  });
}

bool FcGate::wait_for_stamp(std::int64_t stamp_ns,
                            std::chrono::steady_clock::time_point deadline) const {
  std::unique_lock<std::mutex> lock(mutex_);
  return arrived_.wait_until(lock, deadline,
                             [&] { return latest_ && latest_->stamp_ns >= stamp_ns; });
}

bool FcGate::bridge_present() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return required_ || latest_.has_value();
}

std::optional<std::string> FcGate::not_ready_reason() const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!latest_) {
    if (!required_) return std::nullopt;
    return std::string("no state from the flight-controller bridge yet (cover-fc-bridge)");
  }
  const double age_s = clock::ns_to_s(clock::monotonic_ns() - received_monotonic_ns_);
  if (age_s > stale_after_s_) {
    char line[96];
    std::snprintf(line, sizeof line, "flight-controller bridge silent for %.1f s", age_s);
    return std::string(line);
  }
  return wire::fc_not_ready_reason(*latest_);
}

}  // namespace cover::uav_agent
