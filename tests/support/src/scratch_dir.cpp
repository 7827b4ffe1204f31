#include "cover/test/scratch_dir.hpp"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "scratch_listener.hpp"

namespace cover::test {

namespace {

namespace fs = std::filesystem;

// Written into the root of a binary with a failed test: the leftover check
// (tests/support/scratch_check) tells a folder kept for a look from one left behind.
constexpr const char* kKeptMarker = "KEPT";

struct Scratch {
  fs::path root;     // made when the test program starts
  fs::path current;  // the running test's folder, else the root
  std::vector<fs::path> failed;
};

Scratch& scratch() {
  static Scratch state;
  return state;
}

// TempDir() reads TEST_TMPDIR first; temp_directory_path() and child processes read TMPDIR.
void point_environment_at(const fs::path& dir) {
  setenv("TMPDIR", dir.c_str(), 1);
  setenv("TEST_TMPDIR", dir.c_str(), 1);
}

// A test's name as a folder name: parameterised tests have '/' in theirs.
std::string folder_name(std::string name) {
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '-' && c != '_') c = '_';
  }
  return name;
}

// Under the TMPDIR the binary was started with (ctest sets one per build), else /tmp.
fs::path make_root(const std::string& binary) {
  const char* base = std::getenv("TMPDIR");
  std::string pattern =
      (fs::path(base && *base ? base : "/tmp") / ("cover_test_" + binary + "_XXXXXX")).string();
  if (mkdtemp(pattern.data()) == nullptr) {
    throw std::runtime_error("cannot make the scratch directory " + pattern + ": " +
                             std::strerror(errno));
  }
  return pattern;
}

void remove_or_say(const fs::path& dir) {
  std::error_code error;
  fs::remove_all(dir, error);
  if (error) std::fprintf(stderr, "cannot remove %s: %s\n", dir.c_str(), error.message().c_str());
}

class ScratchListener : public ::testing::EmptyTestEventListener {
 public:
  explicit ScratchListener(std::string binary) : binary_(std::move(binary)) {}

  void OnTestProgramStart(const ::testing::UnitTest&) override {
    scratch().root = make_root(binary_);
    scratch().current = scratch().root;
    point_environment_at(scratch().root);
  }

  void OnTestStart(const ::testing::TestInfo& info) override {
    const fs::path dir =
        scratch().root / folder_name(std::string(info.test_suite_name()) + "." + info.name());
    fs::create_directories(dir);
    scratch().current = dir;
    point_environment_at(dir);
  }

  // Runs after the fixture's destructor: what the test's objects remove is gone by then.
  void OnTestEnd(const ::testing::TestInfo& info) override {
    const fs::path dir = scratch().current;
    scratch().current = scratch().root;
    point_environment_at(scratch().root);
    if (info.result()->Failed()) {
      scratch().failed.push_back(dir);
      std::printf("[ SCRATCH  ] kept for a look: %s\n", dir.c_str());
      std::fflush(stdout);
      return;
    }
    remove_or_say(dir);
  }

  void OnTestProgramEnd(const ::testing::UnitTest& unit) override {
    if (scratch().failed.empty() && !unit.Failed()) {
      remove_or_say(scratch().root);
      return;
    }
    std::ofstream marker(scratch().root / kKeptMarker);
    for (const fs::path& dir : scratch().failed) marker << dir.filename().string() << "\n";
    std::printf("[ SCRATCH  ] kept for a look: %s\n", scratch().root.c_str());
  }

 private:
  std::string binary_;
};

}  // namespace

const fs::path& scratch_dir() {
  if (scratch().current.empty()) {
    throw std::logic_error("scratch_dir(): the test binary does not link cover_test_main");
  }
  return scratch().current;
}

std::string scratch_path(const std::string& name) {
  return (scratch_dir() / name).string();
}

void install_scratch_listener(const char* argv0) {
  // A death test's child re-runs one test of the binary: its parent owns the folders.
  if (!GTEST_FLAG_GET(internal_run_death_test).empty()) return;
  ::testing::UnitTest::GetInstance()->listeners().Append(
      new ScratchListener(folder_name(fs::path(argv0).filename().string())));
}

}  // namespace cover::test
