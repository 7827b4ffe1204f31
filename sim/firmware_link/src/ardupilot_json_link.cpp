#include "cover/firmware_link/ardupilot_json_link.hpp"

#include <arpa/inet.h>
#include <poll.h>
#include <spdlog/spdlog.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <system_error>

#include "cover/firmware_link/ardupilot_json_state.hpp"

namespace cover::firmware_link {
namespace {

using Clock = std::chrono::steady_clock;

// Logs the first few of a recurring event, then every 1000th, so a long run's log stays
// readable and still shows that it went on.
bool worth_logging(std::uint64_t count) {
  return count <= 5 || count % 1000 == 0;
}

constexpr std::uint64_t kRateCheckFrames = 5000;

std::chrono::milliseconds until(Clock::time_point deadline) {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
  return std::max(left, std::chrono::milliseconds(0));
}

}  // namespace

ArduPilotJsonLink::ArduPilotJsonLink(const ArduPilotJsonLinkOptions& options)
    : options_(options), port_(options.port) {
  fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd_ < 0) throw std::system_error(errno, std::generic_category(), "ArduPilot JSON socket");
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(options.port));
  if (::inet_pton(AF_INET, options.address.c_str(), &address.sin_addr) != 1 ||
      ::bind(fd_, reinterpret_cast<const sockaddr*>(&address), sizeof(address)) != 0) {
    const int error = errno;
    ::close(fd_);
    throw std::system_error(
        error, std::generic_category(),
        "ArduPilot JSON backend: bind UDP " + options.address + ":" + std::to_string(options.port));
  }
}

ArduPilotJsonLink::~ArduPilotJsonLink() {
  if (fd_ >= 0) ::close(fd_);
}

std::string ArduPilotJsonLink::describe() const {
  return "ArduPilot JSON backend on UDP " + options_.address + ":" + std::to_string(port_) + ", " +
         to_string(options_.pacing);
}

bool ArduPilotJsonLink::wait_for_firmware(std::chrono::milliseconds timeout) {
  if (connected()) return true;
  const auto received = receive(timeout);
  if (!received) return false;
  take(*received);
  spdlog::info("ardupilot json {}: firmware on UDP port {} (frame {}, {} Hz, {} channels)",
               options_.port, ntohs(received->from.sin_port), received->packet.frame_count,
               received->packet.frame_rate_hz, received->packet.channels);
  return true;
}

sim::MotorOutputs ArduPilotJsonLink::exchange(const PlantSample& sample) {
  if (sample.sensors.imu) last_imu_ = *sample.sensors.imu;
  if (held_) {
    const bool lockstep = options_.pacing == Pacing::Lockstep;
    last_answer_ = write_ardupilot_json(ardupilot_json_state(sample, last_imu_, lockstep));
    answer_to_ = held_->from;
    held_.reset();
    send_answer();
    ++stats_.frames_sent;
    // SITL starts at its default 1200 Hz and settles on SIM_RATE_HZ within its first
    // seconds: judged after 5 s of frames.
    const long physics_hz = sample.dt_s > 0.0 ? std::lround(1.0 / sample.dt_s) : 0;
    if (stats_.frames_sent == kRateCheckFrames && ardupilot_.frame_rate_hz != physics_hz) {
      spdlog::warn(
          "ardupilot json {}: the firmware runs {} Hz frames, the physics {} Hz steps: set "
          "SIM_RATE_HZ to the physics rate",
          options_.port, ardupilot_.frame_rate_hz, physics_hz);
    }
  }
  const auto timeout =
      options_.pacing == Pacing::Lockstep ? options_.lockstep_timeout : options_.realtime_timeout;
  if (!await_next(timeout)) {
    ++stats_.answers_missed;
    log_miss();
  }
  return outputs_;
}

bool ArduPilotJsonLink::await_next(std::chrono::milliseconds timeout) {
  const auto deadline = Clock::now() + timeout;
  std::optional<Clock::time_point> repeat_due;  // when a pending repeat is answered again
  std::optional<sockaddr_in> repeat_from;
  while (true) {
    auto wait = until(deadline);
    if (repeat_due) wait = std::min(wait, until(*repeat_due));
    const auto received = receive(wait);
    if (!received) {
      const auto now = Clock::now();
      // No newer frame within the grace (or the wait is over, as a realtime wait soon is):
      // the firmware is still waiting for this one's answer.
      if (repeat_due && (now >= *repeat_due || now >= deadline)) {
        answer_to_ = *repeat_from;
        send_answer();
        ++ardupilot_.repeats_answered;
        if (worth_logging(ardupilot_.repeats_answered)) {
          spdlog::info("ardupilot json {}: frame {} repeated: answered again ({})", options_.port,
                       ardupilot_.last_frame_count, ardupilot_.repeats_answered);
        }
        repeat_due.reset();
      }
      if (now >= deadline) return false;
      continue;
    }
    const bool repeat = !last_answer_.empty() && !held_ &&
                        received->packet.frame_count == ardupilot_.last_frame_count;
    if (repeat) {
      if (!repeat_due) repeat_due = Clock::now() + options_.repeat_grace;
      repeat_from = received->from;
      continue;
    }
    if (repeat_due) ++ardupilot_.repeats_dropped;
    take(*received);
    return true;
  }
}

std::optional<ArduPilotJsonLink::Received> ArduPilotJsonLink::receive(
    std::chrono::milliseconds timeout) {
  const auto deadline = Clock::now() + timeout;
  std::uint8_t buffer[kArduPilotServoPacket32Bytes + 1];
  while (true) {
    pollfd p{fd_, POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(until(deadline).count()));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) return std::nullopt;
    Received received;
    socklen_t from_size = sizeof(received.from);
    // MSG_TRUNC: the datagram's real size, so that a longer one is not taken for a packet.
    const ssize_t size = ::recvfrom(fd_, buffer, sizeof(buffer), MSG_TRUNC,
                                    reinterpret_cast<sockaddr*>(&received.from), &from_size);
    if (size < 0) {
      if (errno == EINTR || errno == EAGAIN) continue;
      return std::nullopt;
    }
    // A longer datagram is cut at sizeof(buffer), a size no packet has.
    const auto parsed = parse_ardupilot_servo_packet(
        buffer, std::min(static_cast<std::size_t>(size), sizeof(buffer)));
    if (parsed.packet) {
      received.packet = *parsed.packet;
      return received;
    }
    ++stats_.frames_rejected;
    if (worth_logging(stats_.frames_rejected)) {
      spdlog::warn("ardupilot json {}: {}-byte datagram refused: {}", options_.port, size,
                   to_string(parsed.error));
    }
    if (Clock::now() >= deadline) return std::nullopt;
  }
}

void ArduPilotJsonLink::take(const Received& received) {
  const std::uint32_t count = received.packet.frame_count;
  if (stats_.answers > 0) {
    const std::uint32_t last = ardupilot_.last_frame_count;
    if (count < last) {
      ++ardupilot_.restarts;
      spdlog::warn("ardupilot json {}: frame_count went back from {} to {}: the firmware restarted",
                   options_.port, last, count);
    } else if (count > last + 1) {
      ardupilot_.frames_skipped += count - last - 1;
      spdlog::warn("ardupilot json {}: frames {}..{} never came", options_.port, last + 1,
                   count - 1);
    }
  }
  ardupilot_.last_frame_count = count;
  ardupilot_.frame_rate_hz = received.packet.frame_rate_hz;
  ++stats_.answers;
  bool spinning = false;
  for (std::size_t i = 0; i < outputs_.size(); ++i) {
    outputs_[i] = ardupilot_pwm_to_output(received.packet.pwm_us[i]);
    spinning = spinning || received.packet.pwm_us[i] > 1000;
  }
  // The packet has no armed flag: a disarmed ArduCopter holds its motors at MOT_PWM_MIN.
  stats_.armed = spinning;
  held_ = received;
}

void ArduPilotJsonLink::send_answer() {
  const ssize_t sent = ::sendto(fd_, last_answer_.data(), last_answer_.size(), 0,
                                reinterpret_cast<const sockaddr*>(&answer_to_), sizeof(answer_to_));
  if (sent != static_cast<ssize_t>(last_answer_.size())) {
    spdlog::warn("ardupilot json {}: answer not sent: {}", options_.port, std::strerror(errno));
  }
}

void ArduPilotJsonLink::log_miss() {
  if (!worth_logging(stats_.answers_missed)) return;
  const auto timeout = options_.pacing == Pacing::Lockstep ? options_.lockstep_timeout
                                                           : options_.realtime_timeout;
  spdlog::warn("ardupilot json {}: no servo packet within {} ms after frame {} ({} missed)",
               options_.port, timeout.count(), ardupilot_.last_frame_count, stats_.answers_missed);
}

}  // namespace cover::firmware_link
