#pragma once

#include <cstdint>

namespace cover::mission {

// What the UAV does once it reaches a process's final point (paper sec. 3.2, scenarios 2-4).
enum class FinalAction : std::uint8_t { None = 0, Land = 1, Deliver = 2 };

const char* to_string(FinalAction action);

}  // namespace cover::mission
