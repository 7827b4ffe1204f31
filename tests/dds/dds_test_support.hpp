#pragma once

#include <unistd.h>

#include <chrono>
#include <functional>
#include <string>
#include <thread>

#include "cover/dds/participant_options.hpp"

namespace cover::test {

// A domain id and topic prefix of this test process's own, so that test binaries run in
// parallel by ctest never see each other's samples.
inline int private_domain_id() {
  return 1 + static_cast<int>(getpid() % 200);
}
inline std::string private_prefix(const std::string& name) {
  return "cover_test/" + name + "/p" + std::to_string(getpid());
}

// Participant options on this process's private domain, for `vendor`.
inline cover::dds::ParticipantOptions private_options(cover::dds::Vendor vendor) {
  cover::dds::ParticipantOptions options;
  options.vendor = vendor;
  options.domain_id = private_domain_id();
  return options;
}

// Polls `condition` every millisecond until it holds or `timeout` passes; its final value.
inline bool wait_until(const std::function<bool()>& condition, std::chrono::milliseconds timeout) {
  const auto give_up = std::chrono::steady_clock::now() + timeout;
  while (!condition()) {
    if (std::chrono::steady_clock::now() >= give_up) return condition();
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}

}  // namespace cover::test
