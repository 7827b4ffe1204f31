#include "cover/dds/participant.hpp"

#include <spdlog/spdlog.h>

#include <thread>

#include "cover/dds/dds_error.hpp"
#include "cover/dds/security_check.hpp"
#include "cyclone/cyclone_backend.hpp"
#include "fastdds/fastdds_backend.hpp"

namespace cover::dds {

Participant::Participant(const ParticipantOptions& options) : options_(options) {
  options_.validate();
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
