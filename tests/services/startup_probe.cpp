// startup_probe: a program built on cover::startup::run_main for the start-up tests, so that
// signals, exit codes and the logger are seen from outside, as a launcher sees a service.
//   startup_probe --mode serve|config-error|dds-like-error|unexpected|return [--code N]
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include <chrono>
#include <iostream>
#include <stdexcept>
#include <string>

#include "cover/config/config_error.hpp"
#include "cover/process/shutdown_signal.hpp"
#include "cover/startup/startup.hpp"

namespace {

// Stands for a library's own error type that a program maps to an exit code of its own
// (dds::DdsError -> 3 in the services).
class ResourceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Says on stdout that it ran its destructor: a clean shutdown unwinds the body.
struct CleanUp {
  ~CleanUp() { std::cout << "cleaned up" << std::endl; }
};

int serve() {
  CleanUp clean_up;
  spdlog::debug("a debug line");
  spdlog::info("an info line");
  std::cout << "ready" << std::endl;
  while (!cover::process::ShutdownSignal::wait_for(std::chrono::milliseconds(1000))) {
  }
  std::cout << "stopping" << std::endl;
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::string mode = "serve";
  int code = 0;
  cover::startup::Program program;
  program.name = "startup_probe";
  program.description = "startup_probe: the start-up library seen from outside";
  program.exit_codes = "Exit codes: 0 stopped; 2 usage; 3 a resource error.";
  program.logger_name = [] { return std::string("probe"); };
  program.add_flags = [&](CLI::App& app) {
    app.add_option("--mode", mode)
        ->check(CLI::IsMember({"serve", "config-error", "resource-error", "unexpected", "return"}));
    app.add_option("--code", code, "--mode return: the exit code");
  };
  program.check_flags = [&](const CLI::App& app) {
    if (app.count("--code") > 0 && mode != "return") {
      throw CLI::ValidationError("--code is only for --mode return");
    }
  };
  program.exits = {cover::startup::exit_on<ResourceError>(3)};
  return cover::startup::run_main(argc, argv, program, [&](const CLI::App&) -> int {
    if (mode == "config-error") throw cover::config::ConfigError("bad key 'x'");
    if (mode == "resource-error") throw ResourceError("port 7 taken");
    if (mode == "unexpected") throw std::logic_error("a bug");
    if (mode == "return") return code;
    return serve();
  });
}
