// The scratch folders themselves: one per test, empty when it starts, where TempDir(),
// temp_directory_path() and child processes write, and gone once a test has passed.
#include "cover/test/scratch_dir.hpp"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace {

namespace fs = std::filesystem;

// Checked by the next test when both run in one process (the binary run by hand).
fs::path g_first_dir;

TEST(ScratchDir, IsTheTestsOwnEmptyFolderAndTheEnvironmentPointsThere) {
  const fs::path dir = cover::test::scratch_dir();
  ASSERT_TRUE(fs::is_directory(dir));
  EXPECT_TRUE(fs::is_empty(dir));
  EXPECT_EQ(dir.filename(), "ScratchDir.IsTheTestsOwnEmptyFolderAndTheEnvironmentPointsThere");
  EXPECT_EQ(fs::temp_directory_path(), dir);
  EXPECT_EQ(::testing::TempDir(), dir.string() + "/");
  EXPECT_EQ(std::string(std::getenv("TMPDIR")), dir.string());  // what children inherit
  EXPECT_EQ(cover::test::scratch_path("a.yaml"), (dir / "a.yaml").string());
  std::ofstream(dir / "a.yaml") << "left for the listener to remove\n";
  fs::create_directories(dir / "nested" / "deeper");
  g_first_dir = dir;
}

TEST(ScratchDir, APassedTestsFolderIsGone) {
  const fs::path dir = cover::test::scratch_dir();
  EXPECT_NE(dir, g_first_dir);
  if (!g_first_dir.empty()) {
    EXPECT_FALSE(fs::exists(g_first_dir)) << g_first_dir;
  }
  // The binary's root holds only the running test's folder.
  for (const auto& entry : fs::directory_iterator(dir.parent_path())) {
    EXPECT_EQ(entry.path(), dir);
  }
}

}  // namespace
