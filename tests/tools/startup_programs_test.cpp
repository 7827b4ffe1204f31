// Every COVER executable through the one start-up (services/startup), run as a user runs it:
// --help exits 0 and states the program's exit codes; an unknown flag exits 2 with the
// program's name and why on stderr, before anything (DDS, a database, a port) starts.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "cover/process/child_process.hpp"
#include "cover/test/file_contents.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/test/time_scale.hpp"

namespace {

using cover::process::ChildProcess;
using cover::process::SpawnOptions;
using namespace std::chrono_literals;

std::vector<std::string> programs() {
  std::vector<std::string> out;
  std::stringstream list(COVER_STARTUP_PROGRAMS);
  std::string path;
  while (std::getline(list, path, '|')) out.push_back(path);
  return out;
}

struct Result {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

Result run(const std::string& program, const std::string& flag) {
  const std::string log =
      cover::test::scratch_path(std::filesystem::path(program).filename().string() + flag + ".log");
  SpawnOptions options;
  options.log_file = log;
  options.null_stdin = true;
  ChildProcess child({program, flag}, options);
  Result r;
  r.exit_code = child.wait(cover::test::scaled(20s)).value_or(-1);
  r.output = cover::test::read_text(log);
  return r;
}

TEST(StartupPrograms, EveryProgramIsChecked) {
  EXPECT_GE(programs().size(), 11u) << COVER_STARTUP_PROGRAMS;
}

TEST(StartupPrograms, HelpExitsZeroAndStatesTheExitCodes) {
  for (const std::string& program : programs()) {
    const Result r = run(program, "--help");
    EXPECT_EQ(r.exit_code, 0) << program << ":\n" << r.output;
    const bool states_them = r.output.find("xit codes") != std::string::npos ||
                             r.output.find(" exit ") != std::string::npos;
    EXPECT_TRUE(states_them) << program << ":\n" << r.output;
  }
}

TEST(StartupPrograms, AnUnknownFlagExitsTwoNamingTheProgramAndWhy) {
  for (const std::string& program : programs()) {
    const Result r = run(program, "--no-such-flag");
    EXPECT_EQ(r.exit_code, 2) << program << ":\n" << r.output;
    // CLI11 names a missing required flag before an unknown one.
    const bool says_why = r.output.find("--no-such-flag") != std::string::npos ||
                          r.output.find("is required") != std::string::npos;
    EXPECT_TRUE(says_why) << program << ":\n" << r.output;
    const std::string name = std::filesystem::path(program).filename().string();
    EXPECT_NE(r.output.find(name), std::string::npos) << program << ":\n" << r.output;
  }
}

}  // namespace
