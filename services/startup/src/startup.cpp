#include "cover/startup/startup.hpp"

#include <CLI/CLI.hpp>

#include <iostream>

#include "cover/config/config_error.hpp"
#include "cover/logging/log.hpp"
#include "cover/process/shutdown_signal.hpp"

namespace cover::startup {
namespace {

constexpr const char* kSeeHelp = "Run with --help for more information.";

// The levels logging::init accepts; spdlog reads anything else as "off", which would
// silence a process that was asked to say more.
const std::vector<std::string> kLogLevels = {"trace", "debug",    "info", "warn",
                                             "error", "critical", "off"};

int report(const std::string& name, const std::exception& e, int exit_code) {
  std::cerr << name << ": " << e.what() << "\n";
  return exit_code;
}

// The exit code of the exception being handled (called inside a catch block).
int exit_code_of(const std::string& name, const std::vector<ExitOn>& exits, int other_exit,
                 const std::exception& e) {
  if (dynamic_cast<const CLI::ParseError*>(&e) != nullptr) {
    std::cerr << name << ": " << e.what() << "\n" << kSeeHelp << "\n";
    return kExitUsage;
  }
  if (dynamic_cast<const config::ConfigError*>(&e) != nullptr) {
    return report(name, e, kExitUsage);
  }
  for (const ExitOn& exit : exits) {
    if (exit.matches && exit.matches(e)) return report(name, e, exit.exit_code);
  }
  return report(name, e, other_exit);
}

}  // namespace

int run_guarded(const std::string& name, const std::vector<ExitOn>& exits, int other_exit,
                const std::function<int()>& body) {
  try {
    return body();
  } catch (const std::exception& e) {
    return exit_code_of(name, exits, other_exit, e);
  }
}

int run_main(int argc, const char* const* argv, const Program& program,
             const std::function<int(const CLI::App&)>& body) {
  if (program.shutdown_signals) process::ShutdownSignal::install();
  CLI::App app{program.description};
  if (!program.exit_codes.empty()) app.footer(program.exit_codes);
  if (program.add_flags) program.add_flags(app);
  std::string log_level;
  if (program.logger_name) {
    app.add_option("--log-level", log_level,
                   "trace | debug | info | warn | error | critical | off (default: "
                   "$COVER_LOG_LEVEL, else info); logs go to stderr")
        ->check(CLI::IsMember(kLogLevels));
  }
  try {
    app.parse(argc, argv);
    if (program.check_flags) program.check_flags(app);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
    std::cerr << program.name << ": " << e.what() << "\n" << kSeeHelp << "\n";
    return kExitUsage;
  }
  if (program.logger_name) logging::init(program.logger_name(), log_level);
  return run_guarded(program.name, program.exits, program.other_exit, [&] { return body(app); });
}

}  // namespace cover::startup
