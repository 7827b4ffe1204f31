#pragma once

#include <cstring>
#include <tuple>

#include "cover/mavlink/hil_messages.hpp"
#include "cover/mavlink/messages.hpp"
#include "cover/mavlink/signing.hpp"

// One instance of each of the codec's 17 messages with every field set to a distinct,
// non-trivial value (negatives, type extremes, extensions set), for round trips and the
// peer tests.
namespace cover::mavlink::test {

// The tests' shared signing key (peer/test_key.js): 32 ASCII bytes.
inline SigningKey test_key(std::uint8_t link_id = 3) {
  SigningKey key;
  std::memcpy(key.secret.data(), "cover-mavlink-test-key-32-bytes!", key.secret.size());
  key.link_id = link_id;
  return key;
}

using AllMessages = std::tuple<Heartbeat, SysStatus, ScaledImu, AttitudeQuaternion, CommandLong,
                               CommandAck, SetAttitudeTarget, AttitudeTarget, HighresImu, Timesync,
                               BatteryStatus, ExtendedSysState, StatusText, HilSensor,
                               HilActuatorControls, HilStateQuaternion, HilGps>;

AllMessages sample_messages();

}  // namespace cover::mavlink::test
