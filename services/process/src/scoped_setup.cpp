#include "cover/process/scoped_setup.hpp"

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <utility>

#include "cover/process/child_process.hpp"

namespace cover::process {

// Set-up and tear-down commands are short scripts: this bounds a hung one.
constexpr std::chrono::seconds kTearDownTimeout{60};

CommandResult run_command(const std::vector<std::string>& argv, const std::string& log_file,
                          std::chrono::milliseconds timeout) {
  SpawnOptions options;
  options.log_file = log_file;
  options.null_stdin = true;
  options.close_other_fds = true;
  CommandResult result;
  ChildProcess child(argv, options);
  if (const auto code = child.wait(timeout)) {
    result.exit_code = *code;
  } else {
    child.terminate();
  }
  std::ifstream log(log_file);
  std::ostringstream text;
  text << log.rdbuf();
  result.output = text.str();
  return result;
}

ScopedSetup::ScopedSetup(const std::vector<std::string>& up, std::vector<std::string> down,
                         std::string log_file)
    : down_(std::move(down)), log_file_(std::move(log_file)) {
  up_ = run_command(up, log_file_, kTearDownTimeout);
}

ScopedSetup::~ScopedSetup() {
  const std::string down_log = log_file_ + ".down";
  try {
    const CommandResult down = run_command(down_, down_log, kTearDownTimeout);
    if (down.exit_code != 0) {
      std::cerr << "tear-down failed: " << down.output << "\n";
      return;
    }
  } catch (const std::exception& e) {
    std::cerr << "tear-down could not run: " << e.what() << "\n";
    return;
  }
  // The logs say why a set-up or tear-down failed; after both went well they say nothing.
  if (!ok()) return;
  std::error_code ignored;
  std::filesystem::remove(log_file_, ignored);
  std::filesystem::remove(down_log, ignored);
}

}  // namespace cover::process
