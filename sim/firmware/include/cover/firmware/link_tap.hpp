#pragma once

#include <netinet/in.h>

#include <atomic>
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "cover/firmware/timed.hpp"
#include "cover/mavlink/messages.hpp"
#include "cover/mavlink/parser.hpp"

namespace cover::firmware {

// A transparent UDP relay on the companion link, between the firmware and cover-fc-bridge:
// it binds the port the firmware sends its onboard link to (14540 + N), passes every
// datagram on to the bridge's udpin port unchanged, and the bridge's answers back to the
// firmware. On the way it reads the frames (one loopback hop more, tens of microseconds):
// what the bridge receives, message by message with its arrival time (the stream rates the
// firmware gives the bridge), the firmware's COMMAND_ACKs, and what the bridge sends
// (COMMAND_LONGs, setpoints). The firmware's answers to the bridge go only to the link the
// command came on, so this is where the test sees them.
class LinkTap {
 public:
  // Throws std::runtime_error when `firmware_side_port` cannot be bound.
  LinkTap(int firmware_side_port, int bridge_port);
  ~LinkTap();
  LinkTap(const LinkTap&) = delete;
  LinkTap& operator=(const LinkTap&) = delete;

  // Frames of `message_id` from the firmware that arrived in [from_ns, to_ns), per second.
  double rate_hz(std::uint32_t message_id, std::int64_t from_ns, std::int64_t to_ns) const;
  std::size_t frames_from_firmware(std::uint32_t message_id) const;
  std::vector<Timed<mavlink::CommandAck>> acks() const;       // firmware -> bridge
  std::vector<Timed<mavlink::CommandLong>> commands() const;  // bridge -> firmware
  // The newest SET_ATTITUDE_TARGET the bridge sent, and how many.
  std::optional<Timed<mavlink::SetAttitudeTarget>> last_setpoint() const;
  // When the newest HEARTBEAT of the bridge's passed on to the firmware (what ArduCopter's
  // GCS failsafe times its silence from, with MAV_GCS_SYSID the bridge's id).
  std::optional<std::int64_t> last_bridge_heartbeat_ns() const;
  std::uint64_t setpoints() const;
  // Every SET_ATTITUDE_TARGET passed on to the firmware since `since_ns`, and the
  // firmware's ATTITUDE_TARGETs (what it says its setpoint is) to the bridge.
  std::vector<Timed<mavlink::SetAttitudeTarget>> setpoints_since(std::int64_t since_ns) const;
  std::vector<Timed<mavlink::AttitudeTarget>> attitude_targets_since(std::int64_t since_ns) const;

  // Cuts the link both ways (a broken cable, a radio out of range): while cut, every
  // datagram either side sends is dropped here. The bridge's COMMAND_LONGs are still
  // recorded in commands() (what it tried), its setpoints are not (none arrived).
  void cut(bool cut);

 private:
  void run();
  void from_firmware(const std::uint8_t* data, std::size_t size, const sockaddr_in& sender);
  void from_bridge(const std::uint8_t* data, std::size_t size);

  int firmware_fd_ = -1;  // bound to the companion port: the firmware's peer
  int bridge_fd_ = -1;    // an ephemeral port: the bridge's peer
  sockaddr_in bridge_{};
  mutable std::mutex mutex_;
  std::optional<sockaddr_in> firmware_;  // where the firmware sends from
  mavlink::StreamParser firmware_parser_;
  mavlink::StreamParser bridge_parser_;
  std::map<std::uint32_t, std::vector<std::int64_t>> arrivals_;
  std::vector<Timed<mavlink::CommandAck>> acks_;
  std::vector<Timed<mavlink::CommandLong>> commands_;
  std::vector<Timed<mavlink::SetAttitudeTarget>> setpoint_log_;
  std::vector<Timed<mavlink::AttitudeTarget>> attitude_targets_;
  std::optional<std::int64_t> last_bridge_heartbeat_ns_;
  std::atomic<bool> cut_{false};
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace cover::firmware
