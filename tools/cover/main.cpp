// cover: COVER's ground-station command line.
#include <CLI/CLI.hpp>

#include <iostream>
#include <optional>

#include "cover/dds/cli_options.hpp"
#include "cover/logging/log.hpp"
#include "cover/process/shutdown_signal.hpp"
#include "fc_commands.hpp"
#include "fleet_commands.hpp"
#include "record_commands.hpp"
#include "security_commands.hpp"
#include "task_commands.hpp"
#include "topic_commands.hpp"

int main(int argc, char** argv) {
  cover::process::ShutdownSignal::install();
  // Logs (e.g. a certificate about to expire) go to stderr: stdout carries samples and JSON.
  cover::logging::init("cover");
  CLI::App app{"cover: ground station for COVER cross-vehicle missions"};
  app.require_subcommand(1);

  bool topics_json = false;
  bool topics_markdown = false;
  auto* topics = app.add_subcommand("topics", "List the topic catalogue");
  auto* json_flag = topics->add_flag("--json", topics_json, "JSON lines instead of a table");
  topics->add_flag("--markdown", topics_markdown, "The table of docs/topics.md")
      ->excludes(json_flag);

  cover::cli::EchoRequest echo_request;
  cover::dds::DdsCliOptions echo_dds;
  auto* echo = app.add_subcommand("echo", "Print samples of a topic as they arrive");
  echo->add_option("topic", echo_request.topic, "e.g. cover/ugv/0/imu")->required();
  echo->add_option("--count", echo_request.count, "Stop after N samples (default: never)");
  echo->add_option("--timeout", echo_request.timeout_s,
                   "Give up after S seconds without all samples");
  echo->add_flag("--json", echo_request.json, "One compact JSON object per line");
  echo_dds.add_to(*echo);

  cover::cli::PubRequest pub_request;
  cover::dds::DdsCliOptions pub_dds;
  auto* pub = app.add_subcommand("pub", "Publish a sample given as JSON");
  pub->add_option("topic", pub_request.topic, "e.g. cover/uav/0/cmd")->required();
  pub->add_option("json", pub_request.json, "Sample as JSON; missing fields are zero")->required();
  pub->add_option("--rate", pub_request.rate_hz, "Publish at HZ (default: once)");
  pub->add_option("--count", pub_request.count, "Number of samples (default 1)");
  pub->add_option("--wait", pub_request.wait_for_reader_s,
                  "Seconds to wait for a subscriber before publishing")
      ->capture_default_str();
  pub_dds.add_to(*pub);
  pub->footer(cover::cli::pub_help_footer());

  // Task commands (the task manager's ground-station side).
  cover::cli::TaskCommandOptions task_options;
  cover::dds::DdsCliOptions task_dds;
  auto add_task_flags = [&](CLI::App* command) {
    command
        ->add_option("--timeout", task_options.timeout_s,
                     "seconds to reach the task manager and get its answer")
        ->capture_default_str();
    command->add_flag("--json", task_options.json, "JSON instead of text");
    task_dds.add_to(*command);
  };
  cover::cli::SubmitRequest submit_request;
  auto* submit = app.add_subcommand(
      "submit", "Submit a task file (config/tasks/*.yaml format, docs/tasks.md); prints its id");
  submit->add_option("file", submit_request.file, "task YAML")->required();
  submit->add_option("--uav", submit_request.uav,
                     "fly it on this UAV (default: the file's uav_id)");
  submit->add_flag("--wait", submit_request.wait,
                   "follow it to the end; exit 0 only if it succeeded");
  add_task_flags(submit);
  bool list_all = false;
  auto* list = app.add_subcommand("list", "The tasks queued and in flight");
  list->add_flag("--all", list_all, "also the ended ones");
  add_task_flags(list);
  std::string task_id;
  auto* status = app.add_subcommand("status", "One task's record");
  status->add_option("id", task_id, "task id")->required();
  add_task_flags(status);
  auto* watch = app.add_subcommand(
      "watch", "Follow a task: a line per change (redrawn in place on a terminal) until it ends");
  watch->add_option("id", task_id, "task id")->required();
  add_task_flags(watch);
  std::string abort_reason;
  auto* abort = app.add_subcommand(
      "abort", "Abort a task: queued, it is dropped; flying, the UAV holds then lands/hovers");
  abort->add_option("id", task_id, "task id")->required();
  abort->add_option("--reason", abort_reason, "recorded with the abort");
  add_task_flags(abort);
  cover::cli::FcCommands fc_commands(app);
  cover::cli::FleetCommand fleet_command(app);
  cover::cli::RecordCommands record_commands(app);
  // DDS-Security fleet directories (docs/security.md).
  auto* security = app.add_subcommand("security", "Make and check DDS-Security fleet directories");
  security->require_subcommand(1);
  cover::cli::SecurityInitRequest init_request;
  auto* security_init = security->add_subcommand(
      "init", "Make a CA, one identity per process, signed governance and permissions");
  security_init->add_option("dir", init_request.directory, "new fleet directory")->required();
  security_init->add_option("--ugvs", init_request.fleet.ugvs, "UGV agents")->capture_default_str();
  security_init->add_option("--uavs", init_request.fleet.uavs, "UAV agents")->capture_default_str();
  security_init
      ->add_option("--ground-stations", init_request.fleet.ground_stations, "ground stations")
      ->capture_default_str();
  security_init
      ->add_option("--days", init_request.days, "validity of every certificate and permission")
      ->capture_default_str();
  security_init
      ->add_option("--vendor", init_request.vendor,
                   "the DDS vendor every process of the fleet runs: fastdds | cyclone")
      ->capture_default_str();
  std::string check_directory;
  bool check_json = false;
  auto* security_check = security->add_subcommand(
      "check", "Per identity: what it may publish and subscribe, when it expires");
  security_check->add_option("dir", check_directory, "fleet directory")->required();
  security_check->add_flag("--json", check_json, "one JSON object");
  std::optional<int> check_warning_days;
  security_check->add_option("--warning-days", check_warning_days,
                             "fail (exit 4) when the CA or an identity expires within N days "
                             "(default: security.expiry_warning_days of config/dds.yaml)");
  security_init->footer(
      "Exit: 0 made and checked, 2 a bad request or an existing directory, 3 openssl failed.");
  security_check->footer(
      "Exit: 0 the CA and every identity valid beyond the warning window, 1 one broken, "
      "expired or mis-signed, 2 DIR is not a fleet directory, 4 all valid but one (or the CA) "
      "expires within the window.");
  app.footer(
      "Task commands exit 0 when accepted / found / succeeded, 1 when rejected, unknown or not\n"
      "succeeded, 2 on a bad file or usage, 3 when no task manager answers within --timeout.");

  CLI11_PARSE(app, argc, argv);
  try {
    if (*topics) {
      using cover::cli::TopicsFormat;
      return cover::cli::list_topics(topics_json       ? TopicsFormat::Json
                                     : topics_markdown ? TopicsFormat::Markdown
                                                       : TopicsFormat::Table);
    }
    if (fc_commands.chosen()) return fc_commands.run();
    if (fleet_command.chosen()) return fleet_command.run();
    if (record_commands.chosen()) return record_commands.run();
    if (*security_init) return cover::cli::security_init(init_request);
    if (*security_check) {
      return cover::cli::security_check(check_directory, check_json, check_warning_days);
    }
    if (*echo) return cover::cli::echo(echo_dds.resolve("cover-echo"), echo_request);
    if (*pub) return cover::cli::publish(pub_dds.resolve("cover-pub"), pub_request);
    const auto station = [&] { return task_dds.resolve("cover-station"); };
    if (*submit) return cover::cli::submit(station(), task_options, submit_request);
    if (*list) return cover::cli::list_tasks(station(), task_options, list_all);
    if (*status) return cover::cli::task_status(station(), task_options, task_id);
    if (*watch) return cover::cli::watch(station(), task_options, task_id);
    if (*abort) return cover::cli::abort_task(station(), task_options, task_id, abort_reason);
  } catch (const std::exception& e) {
    std::cerr << "cover: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
