#pragma once

#include <unistd.h>

#include <string>

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

}  // namespace cover::test
