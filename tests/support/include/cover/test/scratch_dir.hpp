#pragma once

#include <filesystem>
#include <string>

// Every test binary linked with cover_test_main gives each test a scratch directory of its
// own: nothing a test writes outlives it unless it fails, and then its files are kept for a
// look (their path printed). While a test runs, TMPDIR and TEST_TMPDIR point at its
// directory, so ::testing::TempDir(), std::filesystem::temp_directory_path() and every
// child process the test starts write there too.
namespace cover::test {

// The running test's scratch directory. Outside a test (a suite's set-up, a static object)
// the binary's scratch root, which holds the tests' directories and goes with the last.
const std::filesystem::path& scratch_dir();

// `name` inside scratch_dir().
std::string scratch_path(const std::string& name);

}  // namespace cover::test
