#pragma once

#include <cstdint>

namespace cover::model {

// The three stages of one transition process Gi -> Gj (paper sec. 3.2).
// initial: reference frame Gi; transition and final: reference frame Gj.
enum class Stage : std::uint8_t { Initial = 0, Transition = 1, Final = 2 };

inline const char* to_string(Stage stage) {
  switch (stage) {
    case Stage::Initial:
      return "initial";
    case Stage::Transition:
      return "transition";
    case Stage::Final:
      return "final";
  }
  return "unknown";
}

}  // namespace cover::model
