#include "cover/firmware_link/firmware_link.hpp"

namespace cover::firmware_link {

const char* to_string(Pacing pacing) {
  switch (pacing) {
    case Pacing::Lockstep:
      return "lockstep";
    case Pacing::Realtime:
      return "realtime";
  }
  return "unknown";
}

}  // namespace cover::firmware_link
