#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "cover/sim/closed_loop.hpp"

namespace cover::sim {

// A number for JSON: NaN (not measured) becomes null.
nlohmann::json number_or_null(double value);

// The run's headline metrics (what `cover-bench scenario --json` prints).
nlohmann::json summary_json(const ClosedLoopResult& result);

// The run's headline metrics as indented lines a person reads (result, landing and
// delivery errors, tracking, transitions, duration, controller timing).
std::string readable_summary(const ClosedLoopResult& result);

// Writes result.step_trace (ClosedLoopOptions::record_step_trace) as CSV, one line per
// control step: time, stage, frame, the true relative position and velocity, the reference
// position, the command and the disturbance estimate. False if not writable.
bool write_step_trace(const ClosedLoopResult& result, const std::string& path);

// Inserts `suffix` before the extension: ("out/fig.svg", "coni-mpc") -> "out/fig_coni-mpc.svg".
std::string with_suffix(const std::string& path, const std::string& suffix);

}  // namespace cover::sim
