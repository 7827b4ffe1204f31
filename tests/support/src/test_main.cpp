// main() of every COVER test binary: GoogleTest's, plus the per-test scratch directories.
#include <gtest/gtest.h>

#include "scratch_listener.hpp"

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  cover::test::install_scratch_listener(argc > 0 ? argv[0] : "test");
  return RUN_ALL_TESTS();
}
