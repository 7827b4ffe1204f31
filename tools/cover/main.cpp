// cover: COVER's ground-station command line. Each family of subcommands declares its own
// flags and runs itself; main only picks the one the command line chose.
#include <CLI/CLI.hpp>

#include <iostream>

#include "cover/logging/log.hpp"
#include "cover/process/shutdown_signal.hpp"
#include "fc_commands.hpp"
#include "fleet_commands.hpp"
#include "record_commands.hpp"
#include "security_cli.hpp"
#include "task_cli.hpp"
#include "topic_cli.hpp"

int main(int argc, char** argv) {
  cover::process::ShutdownSignal::install();
  // Logs (e.g. a certificate about to expire) go to stderr: stdout carries samples and JSON.
  cover::logging::init("cover");
  CLI::App app{"cover: ground station for COVER cross-vehicle missions"};
  app.require_subcommand(1);
  cover::cli::TopicCli topic_cli(app);
  cover::cli::TaskCli task_cli(app);
  cover::cli::FcCommands fc_commands(app);
  cover::cli::FleetCommand fleet_command(app);
  cover::cli::RecordCommands record_commands(app);
  cover::cli::SecurityCli security_cli(app);
  app.footer(
      "Task commands exit 0 when accepted / found / succeeded, 1 when rejected, unknown or not\n"
      "succeeded, 2 on a bad file or usage, 3 when no task manager answers within --timeout.");

  CLI11_PARSE(app, argc, argv);
  try {
    if (topic_cli.chosen()) return topic_cli.run();
    if (task_cli.chosen()) return task_cli.run();
    if (fc_commands.chosen()) return fc_commands.run();
    if (fleet_command.chosen()) return fleet_command.run();
    if (record_commands.chosen()) return record_commands.run();
    if (security_cli.chosen()) return security_cli.run();
  } catch (const std::exception& e) {
    std::cerr << "cover: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
