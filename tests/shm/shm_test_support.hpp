#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "cover/shm/segment.hpp"
#include "cover/shm/segment_name.hpp"
#include "shm_test_payload.hpp"

namespace cover::shm::test {

inline bool segment_exists(const std::string& name) {
  return std::filesystem::exists(segment_path(name));
}

// Hands out segment names unique to this process and test, and checks after the test
// that none of them is left in /dev/shm (then removes it, so one failure stays one).
class ShmFixture : public ::testing::Test {
 protected:
  std::string unique_name() {
    const std::string run_id = "test" + std::to_string(getpid()) + "_" +
                               std::to_string(names_.size()) + "_" +
                               ::testing::UnitTest::GetInstance()->current_test_info()->name();
    names_.push_back(segment_name(0, run_id.substr(0, 40)));
    return names_.back();
  }

  void TearDown() override {
    for (const auto& name : names_) {
      EXPECT_FALSE(segment_exists(name)) << name << " was left in /dev/shm";
      remove_segment(name);
    }
  }

 private:
  std::vector<std::string> names_;
};

}  // namespace cover::shm::test
