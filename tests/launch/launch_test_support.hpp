#pragma once
// What cover-launch's process tests share: the launcher started as a child with its stdout
// captured, conditions polled with deadlines, the run folder's logs read back.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cover/process/child_process.hpp"
#include "cover/test/file_contents.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/test/time_scale.hpp"
#include "cover/test/wait_until.hpp"

namespace cover::launch::testing {

namespace fs = std::filesystem;
using std::chrono::milliseconds;
using std::chrono::steady_clock;

using cover::test::scaled;
using cover::test::time_scale;

struct LaunchResult {
  int exit_code = -1;
  std::string out;
  std::string err;
  nlohmann::json json() const { return nlohmann::json::parse(out); }
};

using cover::test::read_text;

inline bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// Waits for `condition` (polled every 2 ms) until it holds or `timeout` (scaled) passes.
inline bool eventually(const std::function<bool()>& condition,
                       milliseconds timeout = milliseconds(5000)) {
  return cover::test::wait_until(condition, timeout, milliseconds(2));
}

inline bool pid_gone(int pid) {
  return kill(pid, 0) == -1 && errno == ESRCH;
}

inline std::size_t count(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (auto at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

// The pid in the launcher's "started NAME pid P..." lines, in order.
inline std::vector<int> started_pids(const std::string& launch_log, const std::string& name) {
  std::vector<int> pids;
  const std::string prefix = "started " + name + " pid ";
  for (auto at = launch_log.find(prefix); at != std::string::npos;
       at = launch_log.find(prefix, at + 1)) {
    pids.push_back(std::stoi(launch_log.substr(at + prefix.size())));
  }
  return pids;
}

class LaunchProcess : public ::testing::Test {
 protected:
  // The test's scratch folder: kept for a look when the test fails.
  void SetUp() override {
    dir_ = cover::test::scratch_dir();
    run_dir_ = dir_ / "run";
  }

  std::string write_launch(const std::string& yaml) {
    const auto path = dir_ / "launch.yaml";
    std::ofstream(path) << yaml;
    return path.string();
  }

  // `own_group`: the launcher leads a process group, which a test may signal as a whole.
  // `env`: "KEY=value" in the launcher's environment, as a user exports them.
  std::unique_ptr<cover::process::ChildProcess> start(std::vector<std::string> args,
                                                      bool own_group = false,
                                                      std::vector<std::string> env = {}) {
    args.insert(args.begin(), COVER_LAUNCH);
    cover::process::SpawnOptions options;
    options.extra_env = std::move(env);
    options.capture_stdout = true;
    options.new_process_group = own_group;
    options.log_file = (dir_ / "launcher.stderr").string();
    return std::make_unique<cover::process::ChildProcess>(args, options);
  }

  LaunchResult finish(cover::process::ChildProcess& launcher,
                      milliseconds timeout = milliseconds(8000)) {
    const auto deadline = steady_clock::now() + scaled(timeout);
    LaunchResult result;
    while (auto line = launcher.read_line(
               std::chrono::duration_cast<milliseconds>(deadline - steady_clock::now()))) {
      result.out += *line + "\n";
    }
    const auto left = std::chrono::duration_cast<milliseconds>(deadline - steady_clock::now());
    const auto code = launcher.wait(std::max(left, milliseconds(0)));
    EXPECT_TRUE(code.has_value()) << "cover-launch did not finish in time";
    result.exit_code = code.value_or(-1);
    result.err = read_text(dir_ / "launcher.stderr");
    return result;
  }

  LaunchResult run(const std::string& yaml, std::vector<std::string> flags = {},
                   std::vector<std::string> env = {}) {
    std::vector<std::string> args{write_launch(yaml), "--run-dir", run_dir_.string()};
    args.insert(args.end(), flags.begin(), flags.end());
    auto launcher = start(args, /*own_group=*/false, std::move(env));
    return finish(*launcher);
  }

  std::string log_of(const std::string& name) const {
    return read_text(run_dir_ / (name + ".log"));
  }
  std::string launch_log() const { return read_text(run_dir_ / "launch.log"); }

  // The pid a fake_process printed first in its log ("pid: N"), -1 when none yet.
  int pid_of(const std::string& name) const {
    const std::string log = log_of(name);
    const auto at = log.rfind("pid: ");
    return at == std::string::npos ? -1 : std::stoi(log.substr(at + 5));
  }

  static void expect_all_gone(const nlohmann::json& report) {
    for (const auto& process : report.at("processes")) {
      if (process.at("pid").is_null()) continue;
      EXPECT_TRUE(pid_gone(process.at("pid").get<int>())) << process.dump();
    }
  }

  fs::path dir_;
  fs::path run_dir_;
};

}  // namespace cover::launch::testing
