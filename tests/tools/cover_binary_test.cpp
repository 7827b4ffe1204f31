// tools/cover-bench/cover_binary.hpp: where the benchmarks find a COVER program.
#include "cover_binary.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cover/test/scoped_env.hpp"

namespace {

namespace fs = std::filesystem;

TEST(CoverBinary, TheBuildsOwnProgramsFirst) {
  EXPECT_EQ(fs::path(cover::bench::cover_binary("cover-launch")),
            fs::path(COVER_BUILD_BIN) / "cover-launch");
  // The CLI is built outside bin/.
  EXPECT_EQ(fs::path(cover::bench::cover_binary("cover")), fs::path(COVER_CLI_PATH));
}

TEST(CoverBinary, ThenPathThenTheBareName) {
  cover::test::ScopedEnv path("PATH", "/usr/bin:/bin");
  EXPECT_EQ(cover::bench::cover_binary("sh"), "/usr/bin/sh");
  EXPECT_EQ(cover::bench::cover_binary("cover-no-such-program"), "cover-no-such-program");
}

}  // namespace
