#pragma once

#include <string>

#include "cover/dds/participant_options.hpp"

namespace cover::cli {

// What every task command shares.
struct TaskCommandOptions {
  double timeout_s = 5.0;  // to reach the task manager and get its answer
  bool json = false;
};

// Exit codes of the task commands.
inline constexpr int kTaskOk = 0;         // accepted / found / succeeded
inline constexpr int kTaskRefused = 1;    // rejected, unknown id, or the task did not succeed
inline constexpr int kTaskBadInput = 2;   // bad task file or usage
inline constexpr int kTaskNoManager = 3;  // no task manager reachable

struct SubmitRequest {
  std::string file;
  int uav = -1;       // >= 0: fly it on this UAV instead of the file's uav_id
  bool wait = false;  // and follow it to the end (exit code by its result)
};
// `cover submit`: a submission the manager must hold (a vehicle it has not heard yet) is
// answered at once with what it waits for, printed as it comes ("waiting for UGV 7 (not
// heard yet ...)"); the decision follows, within the client's decision timeout (60 s).
int submit(const dds::ParticipantOptions& dds, const TaskCommandOptions& options,
           const SubmitRequest& request);
// `cover list`: one line per task; a line saying there is none when there is none.
int list_tasks(const dds::ParticipantOptions& dds, const TaskCommandOptions& options, bool all);
int task_status(const dds::ParticipantOptions& dds, const TaskCommandOptions& options,
                const std::string& task_id);
// A live line per change until the task ends; exit code by its result.
int watch(const dds::ParticipantOptions& dds, const TaskCommandOptions& options,
          const std::string& task_id);
int abort_task(const dds::ParticipantOptions& dds, const TaskCommandOptions& options,
               const std::string& task_id, const std::string& reason);

}  // namespace cover::cli
