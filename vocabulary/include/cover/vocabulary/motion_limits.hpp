#pragma once

namespace cover::mission {

// A process's speed and acceleration limits, relative to its reference UGV (paper eq. 15),
// defined here once. The planner, the radial approach, the benchmarks' bounds and the task
// manager take a process's own values; these are what they default to and what bounds them.

// A process that names no limits flies with these (m/s, m/s^2).
inline constexpr double kDefaultVmax_m_s = 1.0;
inline constexpr double kDefaultAmax_m_s2 = 2.0;

// Above these a task's limits are a unit or sign mistake (Task::validate rejects them); a
// configuration that accepts more (the task manager's vehicle limits) or plans less (the
// planner's sanity bounds) disagrees with every task, and is rejected at load.
inline constexpr double kPlausibleVmax_m_s = 20.0;
inline constexpr double kPlausibleAmax_m_s2 = 30.0;

}  // namespace cover::mission
