#pragma once

namespace cover::launch {

// Whether the launcher restarts a process that dies before the run is over, so a standing
// system (simulator, agents, a task manager) survives one failing service.
struct RespawnPolicy {
  bool enabled = false;  // `respawn:`; never with ends_run (its exit is the end of the run)
  // `respawn_delay_s:` (>= 0): the wait before each restart, so a process that crashes at
  // start does not spin. Sensor agents default to kSensorRespawnDelay_s.
  double delay_s = 1.0;
  // `max_respawns:` (>= 1): one more death is an unexpected death, as without respawn.
  int max_respawns = 10;
};

// The default respawn_delay_s of a sensor agent (cover-ugv-agent, cover-mocap-relay): a UAV
// flying on its samples holds on the last IMU sample from 0.1 s, hovers from 0.2 s (0.1 s
// without a relative state) and lands, its task failed, 1.0 s later (docs/failsafes.md).
// A restart must be heard inside that: with this delay, 0.13-0.26 s from the death to the
// first sample heard on Cyclone DDS (cover-bench respawn, docs/failsafes.md), against 1.0 s
// of delay alone before. max_respawns still bounds a process that dies at every start.
inline constexpr double kSensorRespawnDelay_s = 0.1;

}  // namespace cover::launch
