#pragma once

namespace cover::fleet {

// How many vehicles one system holds: ids 0..kMaxUavs-1 and 0..kMaxUgvs-1. The one
// definition every part uses (the simulator's shared-memory world is sized by them, the
// task manager and the ground station listen to that many, the agents' --id ranges, a
// scenario's UAVs). Changing one changes the world segment's layout: bump its version.
inline constexpr int kMaxUavs = 4;
inline constexpr int kMaxUgvs = 8;

}  // namespace cover::fleet
