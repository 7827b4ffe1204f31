// cover: COVER's ground-station command line. Each family of subcommands declares its own
// flags and runs itself; main only picks the one the command line chose.
#include <CLI/CLI.hpp>

#include <memory>

#include "cover/startup/startup.hpp"
#include "fc_commands.hpp"
#include "fleet_commands.hpp"
#include "record_commands.hpp"
#include "security_cli.hpp"
#include "task_cli.hpp"
#include "topic_cli.hpp"

namespace {

constexpr const char* kExitCodes =
    "Task commands exit 0 when accepted / found / succeeded, 1 when rejected, unknown or not\n"
    "succeeded, 2 on a bad file or usage, 3 when no task manager answers within --timeout.";

// The command families; each declares its own flags and runs itself when chosen.
struct Commands {
  explicit Commands(CLI::App& app)
      : topic(app), task(app), fc(app), fleet(app), record(app), security(app) {}

  int run() {
    if (topic.chosen()) return topic.run();
    if (task.chosen()) return task.run();
    if (fc.chosen()) return fc.run();
    if (fleet.chosen()) return fleet.run();
    if (record.chosen()) return record.run();
    if (security.chosen()) return security.run();
    return 0;
  }

  cover::cli::TopicCli topic;
  cover::cli::TaskCli task;
  cover::cli::FcCommands fc;
  cover::cli::FleetCommand fleet;
  cover::cli::RecordCommands record;
  cover::cli::SecurityCli security;
};

}  // namespace

int main(int argc, char** argv) {
  std::unique_ptr<Commands> commands;
  cover::startup::Program program;
  program.name = "cover";
  program.description = "cover: ground station for COVER cross-vehicle missions";
  program.exit_codes = kExitCodes;
  // Logs (e.g. a certificate about to expire) go to stderr: stdout carries samples and JSON.
  program.logger_name = [] { return std::string("cover"); };
  program.add_flags = [&](CLI::App& app) {
    app.require_subcommand(1);
    commands = std::make_unique<Commands>(app);
  };
  program.other_exit = 2;  // a bad file, a bad value
  return cover::startup::run_main(argc, argv, program,
                                  [&](const CLI::App&) { return commands->run(); });
}
