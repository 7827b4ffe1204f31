#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <exception>
#include <fstream>
#include <functional>
#include <string>

#include "cover/dds/domain_claim.hpp"
#include "cover/dds/participant_options.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/test/wait_until.hpp"

namespace cover::test {

// Domains 1..110 are the DDS tests' own: the integration tests and the benchmarks use
// fixed domains from 120 up.
constexpr int kFirstPrivateDomain = 1;
constexpr int kLastPrivateDomain = 110;

// A domain id of this test process's own, held for its lifetime (DomainClaim), so that
// test binaries run in parallel by ctest, or by two suites at once, never see each
// other's samples.
inline int private_domain_id() {
  static const cover::dds::DomainClaim claim =
      cover::dds::DomainClaim::claim_any(kFirstPrivateDomain, kLastPrivateDomain);
  return claim.domain();
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

// The message of what `action` throws; "" when it throws nothing.
inline std::string message_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

// Writes `text` to a file `name` in the test's temp folder; its path.
inline std::string write_temp_yaml(const std::string& name, const std::string& text) {
  const std::string path = cover::test::scratch_path(name);
  std::ofstream(path) << text;
  return path;
}

}  // namespace cover::test
