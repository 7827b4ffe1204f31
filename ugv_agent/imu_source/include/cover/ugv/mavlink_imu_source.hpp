#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cover/mavlink/frame.hpp"
#include "cover/mavlink/link.hpp"
#include "cover/mavlink/parser.hpp"
#include "cover/ugv/imu_source.hpp"

namespace cover::ugv {

// Which clock stamps a MAVLink IMU sample:
//  Autopilot: the autopilot's own (HIGHRES_IMU.time_usec, SCALED_IMU.time_boot_ms). In the
//             simulator that is the simulated time, the time base of every other topic.
//  Receive:   the host's system clock when the frame was read (the field: every vehicle
//             stamps with system time; the autopilot's boot time is on no other clock).
//             The link's latency and jitter (a few ms on serial) are in the stamp.
enum class MavlinkStamp { Autopilot, Receive };
std::optional<MavlinkStamp> parse_mavlink_stamp(const std::string& text);  // autopilot|receive

// UGV k's IMU as its own autopilot (PX4, ArduPilot) streams it over MAVLink: HIGHRES_IMU,
// or SCALED_IMU (mG, mrad/s) from an autopilot that sends only that, of IMU 0 of the first
// system heard sending one. FRD body -> FLU: (x, -y, -z). A sample whose stamp equals the
// previous one is a repeat and dropped (counted); an older one and NaN values go on to the
// filter, which rejects them (counted in the agent's status), as with the other sources.
// A link that fails (a serial cable pulled) is reopened every reopen_interval; the source
// stays Ok meanwhile (the agent's health turns unhealthy without samples).
class MavlinkImuSource : public ImuSource {
 public:
  static constexpr std::chrono::milliseconds kReopenInterval{500};

  // Opens the link `url` names (udpin://IP:PORT, udpout://HOST:PORT,
  // serial:///dev/ttyX:BAUD). Throws std::invalid_argument for a malformed URL and
  // std::runtime_error when the link cannot be opened.
  MavlinkImuSource(const std::string& url, MavlinkStamp stamp);

  std::size_t read(std::vector<ImuSample>& out, std::chrono::milliseconds timeout) override;
  std::string describe() const override { return "mavlink:" + url_; }
  ImuSourceStatus status() const override { return status_; }

  const mavlink::ParserStats& parser_stats() const { return parser_.stats(); }
  std::uint64_t repeats() const { return repeats_; }
  std::optional<std::uint8_t> imu_system() const { return imu_system_; }

 private:
  void read_bytes(std::chrono::milliseconds timeout, std::vector<ImuSample>& out);
  void reopen_if_due();
  void on_frame(const mavlink::Frame& frame, std::vector<ImuSample>& out);
  bool from_imu_system(const mavlink::Frame& frame);
  void deliver(ImuSample sample, std::vector<ImuSample>& out);

  std::string url_;
  MavlinkStamp stamp_;
  std::unique_ptr<mavlink::Link> link_;
  mavlink::StreamParser parser_;
  std::array<std::uint8_t, 2048> buffer_{};
  double receive_stamp_s_ = 0.0;  // system clock when the bytes being parsed were read
  std::optional<std::uint8_t> imu_system_;
  bool highres_seen_ = false;
  std::optional<double> last_stamp_s_;
  std::uint64_t repeats_ = 0;
  std::chrono::steady_clock::time_point next_reopen_{};
  ImuSourceStatus status_;
};

}  // namespace cover::ugv
