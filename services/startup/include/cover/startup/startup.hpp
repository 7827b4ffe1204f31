#pragma once

#include <exception>
#include <functional>
#include <string>
#include <vector>

#include "cover/startup/exit_codes.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace cover::startup {

// An exception the body may throw and the exit code it ends the process with. Its message
// goes to stderr as "<program>: <what>".
struct ExitOn {
  std::function<bool(const std::exception&)> matches;
  int exit_code = kExitFailure;
};

template <typename E>
ExitOn exit_on(int exit_code) {
  return {[](const std::exception& e) { return dynamic_cast<const E*>(&e) != nullptr; }, exit_code};
}

// What an executable declares about its start-up; run_main does the rest in one order for
// every program, so that flags, logging, signals and exit codes behave alike.
struct Program {
  std::string name;         // "cover-uav-agent": the prefix of every error line on stderr
  std::string description;  // the first line of --help
  std::string exit_codes;   // --help's footer: every exit code and what it means here
  // SIGINT/SIGTERM request a clean shutdown (process::ShutdownSignal), installed before
  // anything else starts a thread; a service's body waits on it. False for a one-shot tool,
  // which a signal simply ends.
  bool shutdown_signals = true;
  // The logger's name, asked once the flags are parsed ("uav_agent3"). Empty: no logger is
  // set up and there is no --log-level.
  std::function<std::string()> logger_name;
  std::function<void(CLI::App&)> add_flags;
  // Checks the parsed flags together (what CLI11 cannot express); throws CLI::ParseError
  // (CLI::ValidationError, CLI::RequiredError): a usage error, as a bad flag is.
  std::function<void(const CLI::App&)> check_flags;
  // The body's exceptions and their exit codes, first match wins. A CLI::ParseError and a
  // config::ConfigError come first and always exit kExitUsage; an exception no entry
  // matches exits `other_exit`.
  std::vector<ExitOn> exits;
  int other_exit = kExitFailure;
};

// A whole main(): the signals, the flags (--help prints and exits 0; a bad flag, a missing
// required one or a failed check_flags prints why and exits kExitUsage), the logger
// (--log-level, else $COVER_LOG_LEVEL, else info; on stderr), then `body`, whose return
// value is the exit code and whose exceptions end the process as `program.exits` says.
int run_main(int argc, const char* const* argv, const Program& program,
             const std::function<int(const CLI::App&)>& body);

// The exception mapping alone, for a program that reads its own command line
// (cover-bench's subcommands): `body`'s exit code, or the code of what it threw.
int run_guarded(const std::string& name, const std::vector<ExitOn>& exits, int other_exit,
                const std::function<int()>& body);

}  // namespace cover::startup
