#pragma once

#include <chrono>
#include <cstdint>
#include <string>

#include "cover/firmware_link/plant_sample.hpp"
#include "cover/sim/motor_quadrotor.hpp"

namespace cover::firmware_link {

// How long a link waits for the firmware's answer to a sensor frame: in lockstep until it
// comes (bounded, so that a dead firmware is reported rather than waited for forever); in
// realtime a short while, then the plant goes on holding the last outputs.
enum class Pacing : std::uint8_t { Lockstep, Realtime };
const char* to_string(Pacing pacing);

struct FirmwareLinkStats {
  std::uint64_t frames_sent = 0;      // sensor / state frames to the firmware
  std::uint64_t answers = 0;          // actuator / servo frames taken
  std::uint64_t answers_missed = 0;   // waits that ended without an answer
  std::uint64_t frames_rejected = 0;  // bytes from the firmware that were not a valid frame
  bool armed = false;                 // as the firmware's last answer says (where it says)
};

// The simulator side of one firmware's physics interface (PX4's simulator_mavlink over TCP,
// ArduPilot's JSON backend over UDP). Called from the simulator's thread only.
class FirmwareLink {
 public:
  virtual ~FirmwareLink() = default;

  // Waits up to `timeout` for the firmware to appear (PX4 connecting to the TCP port,
  // ArduPilot's first servo packet); true once it has.
  virtual bool wait_for_firmware(std::chrono::milliseconds timeout) = 0;
  virtual bool connected() const = 0;
  // The plant after a physics step: hands the firmware what is due on it and returns the
  // outputs to hold over the next step (the firmware's order, [0, 1]).
  virtual sim::MotorOutputs exchange(const PlantSample& sample) = 0;

  virtual FirmwareLinkStats stats() const = 0;
  // E.g. "PX4 simulator_mavlink on TCP 127.0.0.1:4560, lockstep".
  virtual std::string describe() const = 0;
};

}  // namespace cover::firmware_link
