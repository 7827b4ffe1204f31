#pragma once

namespace cover::fleet {

// The most vehicles one system can hold: ids 0..kMaxUavs-1 and 0..kMaxUgvs-1. A run's own
// counts are set when it starts (the scenario's UAVs and UGVs, `--uavs N --ugvs M` of the
// processes that listen to a fleet) and written into the simulator's shared-memory world,
// whose readers check them; these bound what a flag or a scenario may ask for, and size
// the world segment's arrays (changing one changes its layout: bump its version).
inline constexpr int kMaxUavs = 32;
inline constexpr int kMaxUgvs = 32;

// How many vehicles a process that listens to a fleet (task manager, recorder, live view,
// `cover fleet`, a UAV agent's accepted UGV ids) expects when not told (--uavs / --ugvs):
// the paper's fleets and the shipped launches up to two_uavs.yaml. A process told nothing
// binds this many vehicles' topics, not kMax's (32 x 32 relative-state topics).
inline constexpr int kDefaultUavs = 4;
inline constexpr int kDefaultUgvs = 8;

static_assert(kDefaultUavs <= kMaxUavs && kDefaultUgvs <= kMaxUgvs);

}  // namespace cover::fleet
