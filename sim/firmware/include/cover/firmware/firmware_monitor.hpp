#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "cover/firmware/byte_transport.hpp"
#include "cover/firmware/timed.hpp"
#include "cover/mavlink/encoder.hpp"
#include "cover/mavlink/messages.hpp"
#include "cover/mavlink/parameter_messages.hpp"
#include "cover/mavlink/parser.hpp"
#include "cover/mavlink/state_messages.hpp"

namespace cover::firmware {

// A parameter as the firmware sent it (PARAM_VALUE).
struct ParamReading {
  float raw = 0.0F;       // param_value as the bytes read
  std::uint8_t type = 0;  // MAV_PARAM_TYPE
  std::array<std::uint8_t, 4> bytes{};
  // The number it means. PX4 puts an integer's bytes in the float field (its
  // PARAM_ENCODE_BYTEWISE: param_get into param_value), ArduPilot the integer cast to float.
  // Decoded here, not by the codec's helper the bridge uses: the tests compare the bridge's
  // values with these, and a shared decoding would hide a shared mistake.
  double value(bool bytewise_integers) const;
};

// The test's own MAVLink connection to a real firmware, beside the bridge's: a ground
// station's (system 255, component 190) on the firmware's GCS port, read by a thread of its
// own. It sees what the firmware says about itself (mode, armed, vertical speed, landed
// state, attitude and rates, texts) independently of what the bridge reports, and plays the
// operator's other path: a mode change as a safety pilot's RC switch or a ground station
// would send it. Its codec is the repository's (services/mavlink); the firmware is the
// independent peer. Every observation is kept with its arrival time.
class FirmwareMonitor {
 public:
  // PX4: its ground-station link, UDP 18570 + N (it answers whoever writes to it).
  static std::unique_ptr<FirmwareMonitor> px4(int instance);
  // ArduCopter: SERIAL0, TCP 5760 + 10 N. ArduCopter streams nothing until asked.
  static std::unique_ptr<FirmwareMonitor> arducopter(int instance);
  explicit FirmwareMonitor(std::unique_ptr<ByteTransport> transport);
  ~FirmwareMonitor();
  FirmwareMonitor(const FirmwareMonitor&) = delete;
  FirmwareMonitor& operator=(const FirmwareMonitor&) = delete;

  // The firmware's own HEARTBEAT (component 1, an autopilot) has come: its system id known.
  bool connected() const;
  std::uint8_t system_id() const;
  std::optional<mavlink::Heartbeat> heartbeat() const;
  std::vector<Timed<mavlink::Heartbeat>> heartbeats_since(std::int64_t since_ns) const;
  std::optional<Timed<mavlink::LocalPositionNed>> position() const;
  std::vector<Timed<mavlink::LocalPositionNed>> positions_since(std::int64_t since_ns) const;
  std::optional<Timed<mavlink::AttitudeQuaternion>> attitude() const;
  std::vector<Timed<mavlink::AttitudeQuaternion>> attitudes_since(std::int64_t since_ns) const;
  std::vector<Timed<mavlink::HighresImu>> imus_since(std::int64_t since_ns) const;
  // ATTITUDE_TARGET: the setpoint the firmware says it flies.
  std::vector<Timed<mavlink::AttitudeTarget>> attitude_targets_since(std::int64_t since_ns) const;
  std::optional<mavlink::ExtendedSysState> extended_state() const;
  std::optional<mavlink::SysStatus> sys_status() const;
  std::vector<Timed<std::string>> texts() const;  // STATUSTEXT, "severity: text"
  // Frames of `message_id` that arrived in [from_ns, to_ns), per second.
  double rate_hz(std::uint32_t message_id, std::int64_t from_ns, std::int64_t to_ns) const;

  // A COMMAND_LONG to the firmware, sent again (confirmation + 1) every 0.5 s until its
  // COMMAND_ACK; the result, or nullopt after `timeout` (a test scales it: COVER_TEST_TIME_SCALE).
  std::optional<std::uint8_t> command(std::uint16_t command, const std::array<float, 7>& params,
                                      std::chrono::milliseconds timeout);
  // SET_MESSAGE_INTERVAL for this link: the result.
  std::optional<std::uint8_t> request_stream(std::uint32_t message_id, double rate_hz);
  // DO_SET_MODE with a custom mode (PX4: main and sub mode; ArduCopter: the mode number).
  std::optional<std::uint8_t> set_mode(float custom_main, float custom_sub = 0.0F);
  // PARAM_REQUEST_READ by name, asked again every 0.5 s; nullopt after `timeout`.
  std::optional<ParamReading> read_param(const std::string& name,
                                         std::chrono::milliseconds timeout);
  // PARAM_SET of `name` to `raw` (the float field as the firmware encodes it) typed `type`
  // (MAV_PARAM_TYPE), sent again every 0.5 s until the firmware's PARAM_VALUE says `raw`;
  // that reading, or nullopt after `timeout`. A ground station's correction of a parameter.
  std::optional<ParamReading> set_param(const std::string& name, float raw, std::uint8_t type,
                                        std::chrono::milliseconds timeout);

 private:
  struct Pending {
    std::vector<std::uint8_t> bytes;
  };
  void run();
  void take(const mavlink::Frame& frame, std::int64_t at_ns);
  void send(const mavlink::EncodedFrame& frame);
  // Sends `request` (again every resend period) until a PARAM_VALUE of `name` arrives after
  // it, carrying `expected_raw`'s bytes when given; nullopt after `timeout`.
  std::optional<ParamReading> exchange_param(const std::string& name,
                                             const mavlink::EncodedFrame& request,
                                             std::optional<float> expected_raw,
                                             std::chrono::milliseconds timeout);
  std::optional<ParamReading> param_since(const std::string& name, std::int64_t since_ns,
                                          std::optional<float> expected_raw) const;

  std::unique_ptr<ByteTransport> transport_;
  mavlink::Encoder encoder_;
  mavlink::StreamParser parser_;
  mutable std::mutex mutex_;
  std::deque<Pending> outgoing_;  // written by the monitor's thread only (see run)
  std::uint8_t system_id_ = 0;
  std::vector<Timed<mavlink::Heartbeat>> heartbeats_;
  std::vector<Timed<mavlink::LocalPositionNed>> positions_;
  std::vector<Timed<mavlink::AttitudeQuaternion>> attitudes_;
  std::vector<Timed<mavlink::HighresImu>> imus_;
  std::vector<Timed<mavlink::AttitudeTarget>> attitude_targets_;
  std::optional<mavlink::ExtendedSysState> extended_state_;
  std::optional<mavlink::SysStatus> sys_status_;
  std::vector<Timed<std::string>> texts_;
  std::vector<Timed<mavlink::CommandAck>> acks_;
  std::vector<Timed<mavlink::ParamValue>> params_;
  std::map<std::uint32_t, std::vector<std::int64_t>> arrivals_;  // by message id
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace cover::firmware
