#pragma once

#include <chrono>
#include <string>
#include <vector>

namespace cover::process {

// The result of one command run to its end.
struct CommandResult {
  int exit_code = -1;  // -1: did not finish within the timeout (then killed)
  std::string output;  // stdout and stderr
};

// Runs `argv` to its end (at most `timeout`), its output collected in `log_file`.
CommandResult run_command(const std::vector<std::string>& argv, const std::string& log_file,
                          std::chrono::milliseconds timeout);

// Sets something up now and tears it down when it goes out of scope, also when a test
// fails or a benchmark throws: e.g. `scripts/wifi-sim up` and `scripts/wifi-sim down`.
class ScopedSetup {
 public:
  ScopedSetup(const std::vector<std::string>& up, std::vector<std::string> down,
              std::string log_file);
  // Runs `down` (whatever `up` did); a failing `down` is logged only. The log files
  // (`log_file`, and `log_file`.down) are kept when either failed, removed otherwise.
  ~ScopedSetup();
  ScopedSetup(const ScopedSetup&) = delete;
  ScopedSetup& operator=(const ScopedSetup&) = delete;

  const CommandResult& up_result() const { return up_; }
  bool ok() const { return up_.exit_code == 0; }

 private:
  CommandResult up_;
  std::vector<std::string> down_;
  std::string log_file_;
};

}  // namespace cover::process
