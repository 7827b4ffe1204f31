#pragma once

#include <nlohmann/json.hpp>

#include <string>

#include "cover/launch/launch_plan.hpp"
#include "cover/launch/supervisor.hpp"

namespace cover::launch {

// The `--json` object: <run_dir>/result.json (written by the ends_run process) if it
// holds a JSON object, else {"result_missing": true}; plus "processes", "run_dir",
// "run_id" and the launcher's "exit_code".
nlohmann::json make_report(const LaunchPlan& plan, const RunOutcome& outcome);

// What the launcher writes to <run_dir>/run.json before it starts any process, so that a
// tool running beside the launch (cover-bench, a test) finds the run by what the launch
// says rather than by guessing: "name", "kind", "run_id" (which {run_id} expands to: the
// simulator's shared-memory segment is /cover_sim_d<domain>_<run_id>), "run_dir",
// "domain" and "launcher_pid".
nlohmann::json make_identity(const LaunchPlan& plan, int launcher_pid);

// A few readable lines: one per process, then how the run ended.
std::string make_summary(const LaunchPlan& plan, const RunOutcome& outcome);

}  // namespace cover::launch
