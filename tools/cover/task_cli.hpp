#pragma once

#include <string>

#include "cover/dds/cli_options.hpp"
#include "task_commands.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace cover::cli {

// `cover submit|list|status|watch|abort`: the task manager's ground-station side
// (task_commands.hpp), each with --timeout, --json and the DDS options.
class TaskCli {
 public:
  explicit TaskCli(CLI::App& app);
  bool chosen() const;
  int run();

 private:
  void add_shared_flags(CLI::App* command);

  CLI::App* submit_ = nullptr;
  CLI::App* list_ = nullptr;
  CLI::App* status_ = nullptr;
  CLI::App* watch_ = nullptr;
  CLI::App* abort_ = nullptr;
  TaskCommandOptions options_;
  dds::DdsCliOptions dds_;
  SubmitRequest submit_request_;
  bool list_all_ = false;
  std::string task_id_;
  std::string abort_reason_;
};

}  // namespace cover::cli
