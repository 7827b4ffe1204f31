#pragma once

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <set>
#include <string>

#include "cover/dds/domain_claim.hpp"
#include "cover/process/child_process.hpp"
#include "cover/test/scratch_dir.hpp"

// What the integration tests share to start COVER's processes and check what they leave.
namespace cover::test {

// A COVER executable built into build/bin.
inline std::string bin(const std::string& name) {
  return std::string(COVER_BIN_DIR) + "/" + name;
}

// A child on `vendor` and `domain`, its output in a log file of the test's scratch folder.
inline process::SpawnOptions quiet(const std::string& vendor, int domain, const std::string& log) {
  process::SpawnOptions options;
  options.extra_env = {"COVER_DDS=" + vendor, "COVER_DDS_DOMAIN=" + std::to_string(domain)};
  options.log_file = scratch_path(log);
  return options;
}

// Holds `domain` (fixed per test, from 120 up; the DDS tests take 1..110) for the test:
// a second suite or a benchmark running at the same time waits instead of mixing its
// processes' samples with this test's.
inline dds::DomainClaim claim_domain(int domain) {
  return dds::DomainClaim::claim(domain, std::chrono::minutes(10));
}

// The names in /dev/shm now.
inline std::set<std::string> shm_entries() {
  std::set<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator("/dev/shm")) {
    names.insert(entry.path().filename().string());
  }
  return names;
}

}  // namespace cover::test
