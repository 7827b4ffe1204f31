#include "cover/dds/participant.hpp"

#include <spdlog/spdlog.h>

#include <fstream>
#include <thread>

#include "cover/dds/dds_error.hpp"
#include "cover/dds/security_check.hpp"
#include "cyclone/cyclone_backend.hpp"
#include "fastdds/fastdds_backend.hpp"

namespace cover::dds {

namespace {

// Linux silently grants at most net.core.rmem_max for a socket's receive buffer; a process
// that asked for more to survive bursts should say it did not get it.
void warn_when_receive_buffer_capped(const ParticipantOptions& options) {
  if (options.vendor != Vendor::FastDds || options.receive_buffer_bytes <= 0) return;
  std::ifstream file("/proc/sys/net/core/rmem_max");
  long long cap_bytes = 0;
  if (!(file >> cap_bytes) || cap_bytes >= options.receive_buffer_bytes) return;
  spdlog::warn(
      "UDP receive buffer capped at {} bytes by net.core.rmem_max ({} asked): samples arriving "
      "while this process is descheduled may be lost; raise it with `sysctl -w "
      "net.core.rmem_max={}`",
      cap_bytes, options.receive_buffer_bytes, options.receive_buffer_bytes);
}

}  // namespace

Participant::Participant(const ParticipantOptions& options) : options_(options) {
  options_.validate();
  warn_when_receive_buffer_capped(options_);
  if (const auto identity = check_participant_security(options_)) {
    const std::string warning = expiry_warning(*identity, options_.security.expiry_warning_days);
    if (!warning.empty()) spdlog::warn("{}", warning);
  }
  backend_ = options_.vendor == Vendor::FastDds ? make_fastdds_participant(options_)
                                                : make_cyclone_participant(options_);
}

Participant::~Participant() = default;

bool wait_until_matched(const std::function<std::size_t()>& matched, std::size_t count,
                        std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (matched() < count) {
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}

}  // namespace cover::dds
