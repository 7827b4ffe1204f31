#pragma once

namespace cover::model {

// The one definition of pi for the controller, the simulator, the UGV filter and the tools
// (M_PI is POSIX, not standard C++). 2 * kPi is exact: it is the double nearest 2 pi.
inline constexpr double kPi = 3.141592653589793;
inline constexpr double kTwoPi = 2.0 * kPi;

}  // namespace cover::model
