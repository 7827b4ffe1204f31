#pragma once
// The simulator side of ArduPilot SITL's JSON physics backend (arducopter --model
// JSON:<ip>) for one UAV: a UDP socket on 9002 + 10 u that takes the firmware's servo
// packet each frame (ardupilot_servo_packet.hpp) and answers its sender with the plant's
// state line (ardupilot_json_state.hpp). ArduPilot blocks on the answer, so in lockstep its
// clock is the physics clock: one answer per servo packet, frame_count + 1 per answer.
#include <netinet/in.h>

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

#include "cover/firmware_link/ardupilot_servo_packet.hpp"
#include "cover/firmware_link/firmware_link.hpp"
#include "cover/sim/uav_imu.hpp"

namespace cover::firmware_link {

struct ArduPilotJsonLinkOptions {
  std::string address = "127.0.0.1";  // where to bind
  int port = 9002;                    // firmware::physics_port(ArduPilot, u)
  Pacing pacing = Pacing::Lockstep;
  // How long exchange() waits for the next servo packet: the firmware's turn in lockstep
  // (bounded so that a dead firmware is reported); in realtime, where the firmware paces
  // itself to the wall clock (a frame a ms), a few frames' time, then the physics steps on.
  std::chrono::milliseconds lockstep_timeout{2000};
  std::chrono::milliseconds realtime_timeout{10};
  // A repeated frame_count is ArduPilot saying it got no answer (it re-sends after ~1 s);
  // it is answered again unless a newer frame follows within this (a repeat that was
  // queued before our answer reached the firmware).
  std::chrono::milliseconds repeat_grace{100};
};

// What happened on the wire beyond FirmwareLinkStats.
struct ArduPilotJsonStats {
  std::uint64_t repeats_answered = 0;  // a repeated frame answered again
  std::uint64_t repeats_dropped = 0;   // a repeated frame a newer one overtook
  std::uint64_t restarts = 0;          // frame_count went back: the firmware restarted
  std::uint64_t frames_skipped = 0;    // frame_count jumped by more than 1
  std::uint32_t last_frame_count = 0;
  std::uint16_t frame_rate_hz = 0;  // the firmware's SIM_RATE_HZ as its packets say
};

class ArduPilotJsonLink final : public FirmwareLink {
 public:
  // Binds the UDP port; throws std::system_error when it cannot.
  explicit ArduPilotJsonLink(const ArduPilotJsonLinkOptions& options);
  ~ArduPilotJsonLink() override;
  ArduPilotJsonLink(const ArduPilotJsonLink&) = delete;
  ArduPilotJsonLink& operator=(const ArduPilotJsonLink&) = delete;

  // Takes the firmware's first servo packet.
  bool wait_for_firmware(std::chrono::milliseconds timeout) override;
  bool connected() const override { return held_.has_value() || stats_.answers > 0; }
  // Answers the servo packet held (the state after the step that applied its outputs),
  // then waits for the next one; returns its motors 1-4 as (pwm - 1000) / 1000. Without an
  // answer in time (counted, logged) the last outputs stay.
  sim::MotorOutputs exchange(const PlantSample& sample) override;

  FirmwareLinkStats stats() const override { return stats_; }
  ArduPilotJsonStats ardupilot_stats() const { return ardupilot_; }
  std::string describe() const override;
  int port() const { return port_; }

 private:
  struct Received {
    ArduPilotServoPacket packet;
    sockaddr_in from{};
  };
  // The next valid servo packet within `timeout`, invalid datagrams counted and skipped.
  std::optional<Received> receive(std::chrono::milliseconds timeout);
  // Waits for a packet newer than the one answered, answering repeats as they come.
  bool await_next(std::chrono::milliseconds timeout);
  void take(const Received& received);
  void send_answer();
  void log_miss();

  ArduPilotJsonLinkOptions options_;
  int fd_ = -1;
  int port_ = 0;
  std::optional<Received> held_;  // taken, not answered yet
  sockaddr_in answer_to_{};       // the sender of the frame answered last
  std::string last_answer_;
  sim::UavImuSample last_imu_;
  sim::MotorOutputs outputs_{};
  FirmwareLinkStats stats_;
  ArduPilotJsonStats ardupilot_;
};

}  // namespace cover::firmware_link
