#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "cover/shm/segment_name.hpp"

using cover::shm::segment_name;
using cover::shm::segment_path;

TEST(ShmSegmentName, JoinsDomainAndRunId) {
  EXPECT_EQ(segment_name(0, "run_1"), "/cover_sim_d0_run_1");
  EXPECT_EQ(segment_name(232, "A9"), "/cover_sim_d232_A9");
  EXPECT_EQ(segment_name(3, std::string(40, 'x')), "/cover_sim_d3_" + std::string(40, 'x'));
}

TEST(ShmSegmentName, RejectsBadRunIdsWithTheReason) {
  for (const std::string bad : {"", "a-b", "a/b", "a b", "ä", "x.y"}) {
    EXPECT_THROW(segment_name(0, bad), std::invalid_argument) << "'" << bad << "'";
  }
  try {
    segment_name(0, std::string(41, 'x'));
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("1 to 40 characters, it has 41"), std::string::npos)
        << e.what();
  }
  try {
    segment_name(0, "bad-id");
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'bad-id'"), std::string::npos) << e.what();
  }
}

TEST(ShmSegmentName, RejectsDomainsOutsideDds) {
  EXPECT_THROW(segment_name(-1, "run"), std::invalid_argument);
  EXPECT_THROW(segment_name(233, "run"), std::invalid_argument);
}

TEST(ShmSegmentName, PathIsUnderDevShm) {
  EXPECT_EQ(segment_path("/cover_sim_d0_run"), "/dev/shm/cover_sim_d0_run");
  EXPECT_EQ(segment_path(segment_name(1, "r")), "/dev/shm/cover_sim_d1_r");
}
