#pragma once

#include <nlohmann/json.hpp>

#include "cover/mavlink/frame.hpp"
#include "cover/mavlink/hil_messages.hpp"
#include "cover/mavlink/messages.hpp"

// The codec's messages as JSON, in the naming the node-mavlink peer uses
// (peer/codec.js): the structs' field names, 64-bit integers as decimal strings, floats
// as their exact double value. Lets a test compare field by field with another
// implementation.
namespace cover::mavlink::test {

nlohmann::json to_json(const Heartbeat& m);
nlohmann::json to_json(const SysStatus& m);
nlohmann::json to_json(const ScaledImu& m);
nlohmann::json to_json(const AttitudeQuaternion& m);
nlohmann::json to_json(const CommandLong& m);
nlohmann::json to_json(const CommandAck& m);
nlohmann::json to_json(const SetAttitudeTarget& m);
nlohmann::json to_json(const AttitudeTarget& m);
nlohmann::json to_json(const HighresImu& m);
nlohmann::json to_json(const Timesync& m);
nlohmann::json to_json(const BatteryStatus& m);
nlohmann::json to_json(const ExtendedSysState& m);
nlohmann::json to_json(const StatusText& m);
nlohmann::json to_json(const HilSensor& m);
nlohmann::json to_json(const HilActuatorControls& m);
nlohmann::json to_json(const HilStateQuaternion& m);
nlohmann::json to_json(const HilGps& m);

// {"message": NAME, "fields": {...}} of a frame of one of the 17 messages; null otherwise.
nlohmann::json frame_to_json(const Frame& frame);

}  // namespace cover::mavlink::test
