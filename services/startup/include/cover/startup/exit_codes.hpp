#pragma once

namespace cover::startup {

// The exit codes every COVER executable shares (docs/exit-codes.md). A program gives 1, 3
// and 4 its own precise meaning in its --help footer; 0, 2 and 130 mean the same
// everywhere, so a launcher, a systemd unit or a script can act on them without knowing
// which program ended.
inline constexpr int kExitOk = 0;  // done, or a service stopped by SIGINT/SIGTERM
// The program's own "did not succeed" (a task rejected, a file found different), or an
// unexpected error: its message on stderr.
inline constexpr int kExitFailure = 1;
// Usage or configuration: a bad flag, a missing file, a parameter out of range. Running
// again unchanged fails the same way; nothing was started.
inline constexpr int kExitUsage = 2;
inline constexpr int kExitCannotStart = 3;      // a resource could not be had (DDS, database, link)
inline constexpr int kExitProgramSpecific = 4;  // each program's own (see its --help)
inline constexpr int kExitInterrupted = 130;  // a run with an end, stopped before it (128 + SIGINT)

}  // namespace cover::startup
