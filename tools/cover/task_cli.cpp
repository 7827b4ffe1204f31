#include "task_cli.hpp"

#include <CLI/CLI.hpp>

namespace cover::cli {

TaskCli::TaskCli(CLI::App& app) {
  submit_ = app.add_subcommand(
      "submit", "Submit a task file (config/tasks/*.yaml format, docs/tasks.md); prints its id");
  submit_->add_option("file", submit_request_.file, "task YAML")->required();
  submit_->add_option("--uav", submit_request_.uav,
                      "fly it on this UAV (default: the file's uav_id)");
  submit_->add_flag("--wait", submit_request_.wait,
                    "follow it to the end; exit 0 only if it succeeded");
  add_shared_flags(submit_);
  list_ = app.add_subcommand("list", "The tasks queued and in flight");
  list_->add_flag("--all", list_all_, "also the ended ones");
  add_shared_flags(list_);
  status_ = app.add_subcommand("status", "One task's record");
  status_->add_option("id", task_id_, "task id")->required();
  add_shared_flags(status_);
  watch_ = app.add_subcommand(
      "watch", "Follow a task: a line per change (redrawn in place on a terminal) until it ends");
  watch_->add_option("id", task_id_, "task id")->required();
  add_shared_flags(watch_);
  abort_ = app.add_subcommand(
      "abort", "Abort a task: queued, it is dropped; flying, the UAV holds then lands/hovers");
  abort_->add_option("id", task_id_, "task id")->required();
  abort_->add_option("--reason", abort_reason_, "recorded with the abort");
  add_shared_flags(abort_);
}

void TaskCli::add_shared_flags(CLI::App* command) {
  command
      ->add_option("--timeout", options_.timeout_s,
                   "seconds to reach the task manager and get its answer")
      ->capture_default_str();
  command->add_flag("--json", options_.json, "JSON instead of text");
  dds_.add_to(*command);
}

bool TaskCli::chosen() const {
  return submit_->parsed() || list_->parsed() || status_->parsed() || watch_->parsed() ||
         abort_->parsed();
}

int TaskCli::run() {
  const dds::ParticipantOptions station = dds_.resolve("cover-station");
  if (submit_->parsed()) return submit(station, options_, submit_request_);
  if (list_->parsed()) return list_tasks(station, options_, list_all_);
  if (status_->parsed()) return task_status(station, options_, task_id_);
  if (watch_->parsed()) return watch(station, options_, task_id_);
  return abort_task(station, options_, task_id_, abort_reason_);
}

}  // namespace cover::cli
