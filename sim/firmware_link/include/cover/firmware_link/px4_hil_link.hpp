#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>

#include "cover/firmware_link/firmware_link.hpp"
#include "cover/firmware_link/px4_hil_frames.hpp"
#include "cover/mavlink/encoder.hpp"
#include "cover/mavlink/parser.hpp"
#include "cover/mavlink/tcp_server_link.hpp"

namespace cover::firmware_link {

struct Px4HilConfig {
  std::string bind_host = "127.0.0.1";
  std::uint16_t port = 4560;  // firmware::physics_port(Px4, N); 0: the kernel's pick (tests)
  Pacing pacing = Pacing::Lockstep;
  // Lockstep: how long a sensor frame waits for its answer before the plant goes on with
  // the last outputs (counted in answers_missed, logged): PX4 stalled, not PX4 slow.
  std::chrono::milliseconds lockstep_timeout{2000};
  // Realtime: the wait for an answer, then the plant goes on (PX4 runs on its own).
  std::chrono::milliseconds realtime_timeout{4};
  // HIL_STATE_QUATERNION (ground truth, PX4 logs it): at most this often, in firmware time.
  double ground_truth_rate_hz = 50.0;
  GeodeticHome home;
  double gravity_m_s2 = 9.81;
};

// What PX4's side of the exchange looked like, beyond FirmwareLinkStats.
struct Px4HilStats {
  std::uint64_t connections = 0;       // PX4 connected (again after a drop: > 1)
  std::uint64_t heartbeats = 0;        // PX4's HEARTBEAT on the simulator link
  std::uint64_t last_sensor_usec = 0;  // the last HIL_SENSOR's time_usec
  std::uint64_t last_answer_usec = 0;  // the last HIL_ACTUATOR_CONTROLS's time_usec
  // PX4 answers each HIL_SENSOR with its own clock, which that frame set: answers whose
  // time is that of the frame being waited for, and answers from a time never sent or
  // earlier than the answer before (not lockstep).
  std::uint64_t answers_matched = 0;
  std::uint64_t answer_time_mismatches = 0;
  std::uint64_t free_run_frames = 0;  // sensor frames sent before PX4's first answer
  mavlink::ParserStats parser;        // the bytes PX4 sent
};

// The simulator end of PX4 SITL's simulator_mavlink for one UAV (real-autopilots notes §2):
// a TCP server PX4 connects to; after each physics step whose IMU sample is due it sends a
// HIL_SENSOR (IMU, + mag, + baro due since the last frame; PX4's clock = the firmware's step time
// in us) and, at ground_truth_rate_hz, a HIL_STATE_QUATERNION; it takes HIL_ACTUATOR_CONTROLS
// controls[0..3] as the motor outputs and `mode` & 128 as armed.
// Lockstep as PX4 expects it: until PX4's first answer the frames are paced at most one
// sensor period of wall time apart (PX4 boots on them, its start script blocked until the
// first); from then on each frame waits for its answer (Pacing). A PX4 that reconnects
// starts over with the free-running boot. Bytes that are not frames are counted, never
// fatal. Called from one thread.
class Px4HilLink final : public FirmwareLink {
 public:
  // Listens at once; throws std::runtime_error when the port cannot be bound.
  explicit Px4HilLink(Px4HilConfig config);
  ~Px4HilLink() override;

  bool wait_for_firmware(std::chrono::milliseconds timeout) override;
  bool connected() const override;
  sim::MotorOutputs exchange(const PlantSample& sample) override;
  FirmwareLinkStats stats() const override;
  std::string describe() const override;

  Px4HilStats px4_stats() const;
  // The port listened on (the kernel's pick when the config said 0), 0 if it could not.
  std::uint16_t port() const { return link_->local_port(); }

 private:
  void send_frames(const PlantSample& sample, std::uint64_t time_usec);
  // Reads and takes what PX4 sent until an answer of time >= `until_usec` or `deadline`;
  // true when one came.
  bool receive_until(std::uint64_t until_usec, std::chrono::steady_clock::time_point deadline);
  void take(const mavlink::Frame& frame, std::uint64_t waiting_for_usec);
  void check_reconnection();
  void write(const mavlink::EncodedFrame& frame);

  Px4HilConfig config_;
  std::unique_ptr<mavlink::TcpServerLink> link_;
  mavlink::Encoder encoder_;
  mavlink::StreamParser parser_;
  FirmwareLinkStats stats_;
  Px4HilStats px4_;
  sim::MotorOutputs outputs_{};
  sim::UavSensorFrame pending_;  // mag / baro samples waiting for the next IMU frame
  bool answered_ = false;        // PX4 answered since it (re)connected: lockstep from now on
  bool answer_arrived_ = false;
  std::uint64_t last_ground_truth_usec_ = 0;
  std::uint64_t last_step_with_imu_ = 0;
  std::chrono::steady_clock::time_point last_free_run_frame_{};
};

}  // namespace cover::firmware_link
