#pragma once

#include <sys/types.h>

#include <chrono>
#include <vector>

namespace cover::process {

// The live processes whose parent is `parent` (from /proc), ascending; an exited child not
// yet waited for (a zombie) is not live.
std::vector<pid_t> live_children(pid_t parent);

// For a tool whose children are services (cover-bench: cover-launch, agents, firmware): on
// SIGINT or SIGTERM each live child is sent SIGINT, as a terminal's Ctrl-C would, and given
// `grace` to stop and clean up behind it (its shared memory, its own children); the ones
// still running are then killed, and this process exits with `exit_code`. Without it a signal to the tool alone kills its children with it
// (SIGKILL: ChildProcess sets PR_SET_PDEATHSIG), and what they would have removed stays.
// Call first in main(), before any thread exists, and not with ShutdownSignal (one of the
// two would take the signal). Returns at once; the watch runs on a thread of its own.
void stop_children_on_shutdown(std::chrono::milliseconds grace, int exit_code);

}  // namespace cover::process
