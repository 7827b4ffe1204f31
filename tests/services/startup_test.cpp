// cover::startup: one start-up for every executable. In process: the flags, the exit codes
// of usage errors and of the body's exceptions. Through a real child (startup_probe): a
// SIGTERM or SIGINT ends a service cleanly with 0, the logger follows --log-level over
// $COVER_LOG_LEVEL, an unexpected exception exits 1 instead of aborting.
#include "cover/startup/startup.hpp"

#include <gtest/gtest.h>

#include <CLI/CLI.hpp>

#include <chrono>
#include <csignal>
#include <functional>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cover/config/config_error.hpp"
#include "cover/process/child_process.hpp"
#include "cover/test/file_contents.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/test/time_scale.hpp"

namespace {

using cover::process::ChildProcess;
using cover::process::SpawnOptions;
using namespace std::chrono_literals;
namespace startup = cover::startup;

class ResourceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// One run of run_main in this process: its exit code, what it printed, whether the body ran.
struct Outcome {
  int exit_code = -1;
  std::string out;
  std::string err;
  bool body_ran = false;
};

// A one-shot program (no signal handling, no logger) with a required --id and a --mode.
startup::Program tool(int& id, std::string& mode) {
  startup::Program program;
  program.name = "tool";
  program.description = "tool: a test program";
  program.exit_codes = "Exit codes: 0 done; 2 usage; 3 a resource error.";
  program.shutdown_signals = false;
  program.add_flags = [&](CLI::App& app) {
    app.add_option("--id", id)->required()->check(CLI::Range(0, 9));
    app.add_option("--mode", mode);
  };
  program.exits = {startup::exit_on<ResourceError>(3), startup::exit_on<std::runtime_error>(4)};
  program.other_exit = 5;
  return program;
}

Outcome run_tool(const std::vector<std::string>& args, const std::function<int()>& body,
                 const std::function<void(startup::Program&)>& adjust = {}) {
  int id = 0;
  std::string mode;
  startup::Program program = tool(id, mode);
  if (adjust) adjust(program);
  std::vector<const char*> argv{"tool"};
  for (const auto& a : args) argv.push_back(a.c_str());
  Outcome result;
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  result.exit_code =
      startup::run_main(static_cast<int>(argv.size()), argv.data(), program, [&](const CLI::App&) {
        result.body_ran = true;
        return body();
      });
  std::cout.flush();  // help goes through std::cout
  result.out = testing::internal::GetCapturedStdout();
  result.err = testing::internal::GetCapturedStderr();
  return result;
}

TEST(Startup, HelpPrintsTheDescriptionAndTheExitCodesAndExitsZero) {
  const Outcome r = run_tool({"--help"}, [] { return 7; });
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_FALSE(r.body_ran);
  EXPECT_NE(r.out.find("tool: a test program"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Exit codes: 0 done; 2 usage; 3 a resource error."), std::string::npos);
  EXPECT_NE(r.out.find("--id"), std::string::npos);
  EXPECT_EQ(r.out.find("--log-level"), std::string::npos) << "a program without a logger";
}

TEST(Startup, AUsageErrorExitsTwoNamingTheProgramAndTheFlagAndNeverRunsTheBody) {
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"--id", "1", "--no-such-flag"}, {}, {"--id", "12"}, {"--id", "x"}}) {
    const Outcome r = run_tool(args, [] { return 0; });
    EXPECT_EQ(r.exit_code, startup::kExitUsage) << r.err;
    EXPECT_FALSE(r.body_ran);
    EXPECT_EQ(r.err.rfind("tool: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("--help"), std::string::npos) << r.err;
  }
  EXPECT_NE(run_tool({"--id", "1", "--no-such-flag"}, [] { return 0; }).err.find("--no-such-flag"),
            std::string::npos);
}

TEST(Startup, AFailedCombinationCheckIsAUsageError) {
  const auto check = [](startup::Program& p) {
    p.check_flags = [](const CLI::App& app) {
      if (app.count("--mode") == 0) throw CLI::ValidationError("--mode is needed with --id 3");
    };
  };
  const Outcome bad = run_tool(
      {"--id", "3"}, [] { return 0; }, check);
  EXPECT_EQ(bad.exit_code, startup::kExitUsage);
  EXPECT_FALSE(bad.body_ran);
  EXPECT_NE(bad.err.find("--mode is needed with --id 3"), std::string::npos) << bad.err;
  EXPECT_EQ(run_tool(
                {"--id", "3", "--mode", "m"}, [] { return 0; }, check)
                .exit_code,
            0);
}

TEST(Startup, TheBodysReturnValueIsTheExitCode) {
  const Outcome r = run_tool({"--id", "1"}, [] { return 42; });
  EXPECT_TRUE(r.body_ran);
  EXPECT_EQ(r.exit_code, 42);
  EXPECT_EQ(r.err, "");
}

TEST(Startup, TheBodysExceptionsMapToExitCodesFirstMatchWins) {
  struct Case {
    std::function<int()> body;
    int exit_code;
    std::string message;
  };
  const std::vector<Case> cases = {
      // Configuration comes first: a ConfigError is a runtime_error, mapped to 4 below.
      {[]() -> int { throw cover::config::ConfigError("bad key"); }, 2, "tool: bad key\n"},
      {[]() -> int { throw CLI::ValidationError("--from: three numbers"); }, 2,
       "tool: --from: three numbers\nRun with --help for more information.\n"},
      {[]() -> int { throw ResourceError("port taken"); }, 3, "tool: port taken\n"},
      {[]() -> int { throw std::runtime_error("other"); }, 4, "tool: other\n"},
      {[]() -> int { throw std::logic_error("a bug"); }, 5, "tool: a bug\n"},
  };
  for (const Case& c : cases) {
    const Outcome r = run_tool({"--id", "1"}, c.body);
    EXPECT_EQ(r.exit_code, c.exit_code) << c.message;
    EXPECT_EQ(r.err, c.message);
  }
}

TEST(Startup, RunGuardedMapsExceptionsAsRunMainDoes) {
  testing::internal::CaptureStderr();
  EXPECT_EQ(startup::run_guarded("bench x", {startup::exit_on<ResourceError>(3)}, 1,
                                 []() -> int { throw ResourceError("no port"); }),
            3);
  EXPECT_EQ(startup::run_guarded("bench x", {}, 1, []() -> int { throw std::logic_error("b"); }),
            1);
  EXPECT_EQ(startup::run_guarded("bench x", {}, 1, [] { return 4; }), 4);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "bench x: no port\nbench x: b\n");
}

// The probe as a launcher runs a service: stdout read line by line, stderr in a log file.
struct Probe {
  explicit Probe(const std::vector<std::string>& args, const std::string& log_level_env = "info")
      : log(cover::test::scratch_path("probe.log")),
        child(argv(args), options(log, log_level_env)) {}

  static std::vector<std::string> argv(const std::vector<std::string>& args) {
    std::vector<std::string> v{STARTUP_PROBE};
    v.insert(v.end(), args.begin(), args.end());
    return v;
  }
  static SpawnOptions options(const std::string& log, const std::string& level) {
    SpawnOptions o;
    o.capture_stdout = true;
    o.log_file = log;
    o.null_stdin = true;
    o.extra_env = {"COVER_LOG_LEVEL=" + level};
    return o;
  }
  // The next line on stdout within a scaled 10 s; empty when none came.
  std::string line() { return child.read_line(cover::test::scaled(10s)).value_or(""); }
  std::string stderr_text() const { return cover::test::read_text(log); }

  std::string log;
  ChildProcess child;
};

TEST(StartupProcess, SigtermAndSigintEndAServiceCleanlyWithZero) {
  for (const int signal_number : {SIGTERM, SIGINT}) {
    Probe probe({"--mode", "serve"});
    ASSERT_EQ(probe.line(), "ready") << probe.stderr_text();
    const int code = probe.child.terminate(cover::test::scaled(10s), signal_number);
    EXPECT_EQ(code, 0) << "signal " << signal_number << ": " << probe.stderr_text();
    EXPECT_EQ(probe.child.killed_by_signal(), 0) << "it ended by itself, not by the signal";
    EXPECT_EQ(probe.line(), "stopping");
    EXPECT_EQ(probe.line(), "cleaned up") << "the body's objects were destroyed";
  }
}

TEST(StartupProcess, TheLoggerFollowsLogLevelOverTheEnvironment) {
  {
    Probe probe({"--mode", "serve"}, "info");
    ASSERT_EQ(probe.line(), "ready");
    probe.child.terminate(cover::test::scaled(10s));
    EXPECT_NE(probe.stderr_text().find("[probe] an info line"), std::string::npos)
        << probe.stderr_text();
    EXPECT_EQ(probe.stderr_text().find("a debug line"), std::string::npos);
  }
  {
    Probe probe({"--mode", "serve", "--log-level", "debug"}, "error");
    ASSERT_EQ(probe.line(), "ready");
    probe.child.terminate(cover::test::scaled(10s));
    EXPECT_NE(probe.stderr_text().find("[probe] a debug line"), std::string::npos)
        << probe.stderr_text();
  }
  {
    Probe probe({"--mode", "serve", "--log-level", "loud"});
    EXPECT_EQ(probe.child.wait(cover::test::scaled(10s)), startup::kExitUsage);
    EXPECT_NE(probe.stderr_text().find("--log-level"), std::string::npos) << probe.stderr_text();
  }
}

TEST(StartupProcess, ExitCodesSeenFromOutside) {
  struct Case {
    std::vector<std::string> args;
    int exit_code;
    std::string on_stderr;
  };
  const std::vector<Case> cases = {
      {{"--mode", "config-error"}, 2, "startup_probe: bad key 'x'"},
      {{"--mode", "resource-error"}, 3, "startup_probe: port 7 taken"},
      {{"--mode", "unexpected"}, 1, "startup_probe: a bug"},
      {{"--mode", "return", "--code", "4"}, 4, ""},
      {{"--code", "4"}, 2, "--code is only for --mode return"},
      {{"--no-such-flag"}, 2, "--no-such-flag"},
      {{"--help"}, 0, ""},
  };
  for (const Case& c : cases) {
    Probe probe(c.args);
    const auto code = probe.child.wait(cover::test::scaled(10s));
    ASSERT_TRUE(code.has_value());
    EXPECT_EQ(*code, c.exit_code) << c.args.back() << ": " << probe.stderr_text();
    EXPECT_EQ(probe.child.killed_by_signal(), 0) << "no abort: " << c.args.back();
    EXPECT_NE(probe.stderr_text().find(c.on_stderr), std::string::npos) << probe.stderr_text();
  }
}

}  // namespace
