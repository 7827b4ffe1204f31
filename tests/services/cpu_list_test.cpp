// cpu_list writes CPUs as taskset and Cpus_allowed_list do; cpus_of reads a cpu_set_t back.
#include "cover/process/cpu_list.hpp"

#include <gtest/gtest.h>

namespace {

using cover::process::cpu_list;

TEST(CpuList, RunsBecomeRangesInAnyOrderRepeatsOnce) {
  EXPECT_EQ(cpu_list({1}), "1");
  EXPECT_EQ(cpu_list({0, 2, 3}), "0,2-3");
  EXPECT_EQ(cpu_list({7, 0, 1, 2, 5, 1}), "0-2,5,7");
  EXPECT_EQ(cpu_list({4, 5, 6, 7}), "4-7");
  EXPECT_EQ(cpu_list({}), "none");
}

TEST(CpuList, ReadsACpuSetBackInOrder) {
  cpu_set_t set;
  CPU_ZERO(&set);
  for (const int cpu : {9, 1, 2, CPU_SETSIZE - 1}) CPU_SET(cpu, &set);
  EXPECT_EQ(cover::process::cpus_of(set), (std::vector<int>{1, 2, 9, CPU_SETSIZE - 1}));
  EXPECT_EQ(cpu_list(cover::process::cpus_of(set)), "1-2,9," + std::to_string(CPU_SETSIZE - 1));
  CPU_ZERO(&set);
  EXPECT_TRUE(cover::process::cpus_of(set).empty());
}

}  // namespace
