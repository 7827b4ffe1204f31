#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>

#include "cover/process/child_process.hpp"

// What the integration tests share to start COVER's processes and check what they leave.
namespace cover::test {

// A COVER executable built into build/bin.
inline std::string bin(const std::string& name) {
  return std::string(COVER_BIN_DIR) + "/" + name;
}

// A child on `vendor` and `domain`, its output in a log file of the test's temp folder.
inline process::SpawnOptions quiet(const std::string& vendor, int domain, const std::string& log) {
  process::SpawnOptions options;
  options.extra_env = {"COVER_DDS=" + vendor, "COVER_DDS_DOMAIN=" + std::to_string(domain)};
  options.log_file = ::testing::TempDir() + log;
  return options;
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
