#pragma once

namespace cover::launch {

// Whether the launcher restarts a process that dies before the run is over, so a standing
// system (simulator, agents, a task manager) survives one failing service.
struct RespawnPolicy {
  bool enabled = false;  // `respawn:`; never with ends_run (its exit is the end of the run)
  // `respawn_delay_s:` (>= 0): the wait before each restart, so a process that crashes at
  // start does not spin.
  double delay_s = 1.0;
  // `max_respawns:` (>= 1): one more death is an unexpected death, as without respawn.
  int max_respawns = 10;
};

}  // namespace cover::launch
