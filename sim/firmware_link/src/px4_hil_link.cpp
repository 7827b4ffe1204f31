#include "cover/firmware_link/px4_hil_link.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <thread>

#include "cover/mavlink/messages.hpp"

namespace cover::firmware_link {
namespace {

using Clock = std::chrono::steady_clock;

// The simulator's MAVLink identity on the link (PX4 does not check it; Gazebo's is 1/51).
constexpr std::uint8_t kSimulatorSystemId = 1;
constexpr std::uint8_t kSimulatorComponentId = 51;  // MAV_COMP_ID_USER27, Gazebo's choice
constexpr std::uint8_t kArmedFlag = 128;            // MAV_MODE_FLAG_SAFETY_ARMED

double clamp_output(float value) {
  if (!std::isfinite(value)) return 0.0;  // a stopped motor, never a NaN into the plant
  return std::clamp(static_cast<double>(value), 0.0, 1.0);
}

}  // namespace

Px4HilLink::Px4HilLink(Px4HilConfig config)
    : config_(std::move(config)),
      link_(mavlink::make_tcp_server_link(config_.bind_host, config_.port)),
      encoder_(kSimulatorSystemId, kSimulatorComponentId) {
  // Bound at construction: a port another simulator holds is an error now, not a PX4 that
  // never connects later.
  if (!link_->open()) throw std::runtime_error("PX4 HIL link: " + link_->last_error());
}

Px4HilLink::~Px4HilLink() = default;

bool Px4HilLink::wait_for_firmware(std::chrono::milliseconds timeout) {
  const auto deadline = Clock::now() + timeout;
  if (!link_->is_open() && !link_->open()) return false;
  while (!link_->has_client() && Clock::now() < deadline) {
    receive_until(std::numeric_limits<std::uint64_t>::max(),
                  std::min(deadline, Clock::now() + std::chrono::milliseconds(20)));
  }
  return link_->has_client();
}

bool Px4HilLink::connected() const {
  return link_->has_client();
}

sim::MotorOutputs Px4HilLink::exchange(const PlantSample& sample) {
  check_reconnection();
  // A magnetometer or barometer sample due between IMU samples (100 Hz mag against a 250 Hz
  // IMU) rides on the next HIL_SENSOR rather than being lost.
  if (sample.sensors.magnetometer) pending_.magnetometer = sample.sensors.magnetometer;
  if (sample.sensors.barometer) pending_.barometer = sample.sensors.barometer;
  if (!sample.sensors.imu) {
    // Between IMU samples PX4 gets nothing (its clock advances only with HIL_SENSOR): take
    // what has come, hold the outputs.
    receive_until(std::numeric_limits<std::uint64_t>::max(), Clock::now());
    return outputs_;
  }
  // PX4's clock must never be 0 (it would fall back to wall time) and must rise strictly.
  std::uint64_t time_usec = static_cast<std::uint64_t>(std::llround(sample.firmware_time_s * 1e6));
  time_usec = std::max(time_usec, px4_.last_sensor_usec + 1);
  if (!link_->has_client()) {
    receive_until(std::numeric_limits<std::uint64_t>::max(), Clock::now());
    if (!link_->has_client()) return outputs_;
    check_reconnection();
  }
  if (!answered_) {
    // Booting: at most one sensor period of wall time per frame, so PX4's start-up (which
    // runs on this clock) is not raced through while it cannot answer yet.
    const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(
        sample.dt_s *
        std::max<double>(1.0, static_cast<double>(sample.firmware_step - last_step_with_imu_))));
    const auto due = last_free_run_frame_ + period;
    receive_until(std::numeric_limits<std::uint64_t>::max(), due);
    last_free_run_frame_ = Clock::now();
  }
  last_step_with_imu_ = sample.firmware_step;
  send_frames(sample, time_usec);
  if (!answered_) {
    ++px4_.free_run_frames;
    receive_until(time_usec, Clock::now());
    return outputs_;
  }
  const auto timeout =
      config_.pacing == Pacing::Lockstep ? config_.lockstep_timeout : config_.realtime_timeout;
  const std::uint64_t connection = px4_.connections;
  if (!receive_until(time_usec, Clock::now() + timeout) && link_->has_client() &&
      px4_.connections == connection) {
    ++stats_.answers_missed;
    if (config_.pacing == Pacing::Lockstep) {
      spdlog::warn(
          "px4 hil {}: no HIL_ACTUATOR_CONTROLS for the HIL_SENSOR of t = {} us within "
          "{} ms ({} missed); holding the last outputs",
          describe(), time_usec, timeout.count(), stats_.answers_missed);
    }
  }
  return outputs_;
}

void Px4HilLink::send_frames(const PlantSample& sample, std::uint64_t time_usec) {
  PlantSample with_pending = sample;
  with_pending.sensors.magnetometer = pending_.magnetometer;
  with_pending.sensors.barometer = pending_.barometer;
  pending_ = {};
  write(encoder_.encode(hil_sensor(with_pending, time_usec)));
  px4_.last_sensor_usec = time_usec;
  const double period_usec = 1e6 / config_.ground_truth_rate_hz;
  if (last_ground_truth_usec_ == 0 ||
      static_cast<double>(time_usec - last_ground_truth_usec_) >= period_usec - 0.5) {
    write(encoder_.encode(
        hil_state_quaternion(sample, time_usec, config_.home, config_.gravity_m_s2)));
    last_ground_truth_usec_ = time_usec;
  }
}

void Px4HilLink::write(const mavlink::EncodedFrame& frame) {
  if (link_->write(frame.bytes.data(), frame.size)) ++stats_.frames_sent;
}

bool Px4HilLink::receive_until(std::uint64_t until_usec, Clock::time_point deadline) {
  std::array<std::uint8_t, 2048> buffer{};
  answer_arrived_ = false;
  const std::uint64_t connection = px4_.connections;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - Clock::now() + std::chrono::microseconds(999));
    const std::size_t n =
        link_->read(buffer.data(), buffer.size(), std::max(left, std::chrono::milliseconds(0)));
    check_reconnection();
    parser_.feed(buffer.data(), n, [&](const mavlink::Frame& f) { take(f, until_usec); });
    stats_.frames_rejected = parser_.stats().errors() + parser_.stats().unknown_ids;
    if (answer_arrived_ && px4_.last_answer_usec >= until_usec) return true;
    // PX4 gone or back as a new connection: nothing will answer this frame.
    if (px4_.connections != connection || !link_->has_client()) return false;
    if (n == 0 && Clock::now() >= deadline) return false;
  }
}

void Px4HilLink::take(const mavlink::Frame& frame, std::uint64_t waiting_for_usec) {
  if (mavlink::decode<mavlink::Heartbeat>(frame)) {
    ++px4_.heartbeats;
    return;
  }
  const auto answer = mavlink::decode<mavlink::HilActuatorControls>(frame);
  if (!answer) return;  // PX4's SET_MESSAGE_INTERVAL for ground truth: we send it anyway
  for (std::size_t i = 0; i < outputs_.size(); ++i) outputs_[i] = clamp_output(answer->controls[i]);
  stats_.armed = (answer->mode & kArmedFlag) != 0;
  ++stats_.answers;
  if (answer->time_usec == waiting_for_usec) ++px4_.answers_matched;
  // PX4's clock is the one our frames set: an answer from a time we never sent, or going
  // back, is not lockstep.
  if (answer->time_usec > px4_.last_sensor_usec || answer->time_usec < px4_.last_answer_usec) {
    ++px4_.answer_time_mismatches;
  }
  px4_.last_answer_usec = answer->time_usec;
  answered_ = true;
  answer_arrived_ = true;
}

void Px4HilLink::check_reconnection() {
  const std::uint64_t accepted = link_->clients_accepted();
  if (accepted == px4_.connections) return;
  px4_.connections = accepted;
  parser_.reset();
  answered_ = false;
  last_free_run_frame_ = Clock::time_point{};
  spdlog::info("px4 hil {}: PX4 connected{}", describe(),
               accepted > 1 ? " again (" + std::to_string(accepted) + " connections)" : "");
}

FirmwareLinkStats Px4HilLink::stats() const {
  return stats_;
}

Px4HilStats Px4HilLink::px4_stats() const {
  Px4HilStats s = px4_;
  s.parser = parser_.stats();
  return s;
}

std::string Px4HilLink::describe() const {
  return "PX4 simulator_mavlink on " + link_->describe() + ", " + to_string(config_.pacing);
}

}  // namespace cover::firmware_link
