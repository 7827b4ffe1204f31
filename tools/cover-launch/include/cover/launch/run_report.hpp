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

// A few readable lines: one per process, then how the run ended.
std::string make_summary(const LaunchPlan& plan, const RunOutcome& outcome);

}  // namespace cover::launch
