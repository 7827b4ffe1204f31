#pragma once

namespace cover::launch {

// cover-launch's exit codes, documented in --help and docs/launch.md.
inline constexpr int kExitCompleted = 0;      // the ends_run process exited with 0
inline constexpr int kExitUsage = 2;          // bad flag or launch file
inline constexpr int kExitEndsRunFailed = 3;  // the ends_run process exited non-zero
inline constexpr int kExitProcessDied = 4;    // a process died early or could not start
inline constexpr int kExitInterrupted = 130;  // SIGINT / SIGTERM to the launcher

}  // namespace cover::launch
