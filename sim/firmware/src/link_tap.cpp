#include "cover/firmware/link_tap.hpp"

#include <arpa/inet.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

#include "cover/clock/clock.hpp"

namespace cover::firmware {
namespace {

namespace mav = cover::mavlink;

sockaddr_in loopback(int port) {
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  return address;
}

int bound_udp(int port) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  sockaddr_in self = loopback(port);
  if (fd < 0 || ::bind(fd, reinterpret_cast<sockaddr*>(&self), sizeof(self)) != 0) {
    const std::string why = strerror(errno);
    if (fd >= 0) ::close(fd);
    throw std::runtime_error("link tap: cannot bind UDP 127.0.0.1:" + std::to_string(port) + ": " +
                             why);
  }
  return fd;
}

}  // namespace

LinkTap::LinkTap(int firmware_side_port, int bridge_port)
    : firmware_fd_(bound_udp(firmware_side_port)),
      bridge_fd_(bound_udp(0)),
      bridge_(loopback(bridge_port)),
      thread_([this] { run(); }) {}

LinkTap::~LinkTap() {
  stop_ = true;
  thread_.join();
  ::close(firmware_fd_);
  ::close(bridge_fd_);
}

void LinkTap::run() {
  std::array<std::uint8_t, 65536> buffer{};
  while (!stop_) {
    std::array<pollfd, 2> fds{{{firmware_fd_, POLLIN, 0}, {bridge_fd_, POLLIN, 0}}};
    if (::poll(fds.data(), fds.size(), 20) <= 0) continue;
    if ((fds[0].revents & POLLIN) != 0) {
      sockaddr_in sender{};
      socklen_t length = sizeof(sender);
      const ssize_t n = ::recvfrom(firmware_fd_, buffer.data(), buffer.size(), 0,
                                   reinterpret_cast<sockaddr*>(&sender), &length);
      if (n > 0) from_firmware(buffer.data(), static_cast<std::size_t>(n), sender);
    }
    if ((fds[1].revents & POLLIN) != 0) {
      const ssize_t n = ::recv(bridge_fd_, buffer.data(), buffer.size(), 0);
      if (n > 0) from_bridge(buffer.data(), static_cast<std::size_t>(n));
    }
  }
}

void LinkTap::from_firmware(const std::uint8_t* data, std::size_t size, const sockaddr_in& sender) {
  if (cut_) return;
  // Passed on first: the reading below must not delay the bridge.
  ::sendto(bridge_fd_, data, size, 0, reinterpret_cast<const sockaddr*>(&bridge_), sizeof(bridge_));
  const std::int64_t at_ns = clock::monotonic_ns();
  std::lock_guard<std::mutex> lock(mutex_);
  firmware_ = sender;
  firmware_parser_.feed(data, size, [&](const mav::Frame& frame) {
    arrivals_[frame.message_id].push_back(at_ns);
    if (const auto ack = mav::decode<mav::CommandAck>(frame)) {
      acks_.push_back({at_ns, *ack});
    } else if (const auto target = mav::decode<mav::AttitudeTarget>(frame)) {
      attitude_targets_.push_back({at_ns, *target});
    }
  });
}

void LinkTap::from_bridge(const std::uint8_t* data, std::size_t size) {
  const bool cut = cut_;
  std::optional<sockaddr_in> firmware;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    firmware = firmware_;
  }
  // Nothing to answer before the firmware has written: the bridge (udpin) writes only
  // after it has heard it, so nothing is lost.
  if (firmware && !cut) {
    ::sendto(firmware_fd_, data, size, 0, reinterpret_cast<const sockaddr*>(&*firmware),
             sizeof(*firmware));
  }
  const std::int64_t at_ns = clock::monotonic_ns();
  std::lock_guard<std::mutex> lock(mutex_);
  bridge_parser_.feed(data, size, [&](const mav::Frame& frame) {
    if (const auto command = mav::decode<mav::CommandLong>(frame)) {
      commands_.push_back({at_ns, *command});  // what the bridge did, delivered or not
    } else if (const auto setpoint = mav::decode<mav::SetAttitudeTarget>(frame); setpoint && !cut) {
      setpoint_log_.push_back({at_ns, *setpoint});
    } else if (frame.message_id == mav::Heartbeat::kId && !cut) {
      last_bridge_heartbeat_ns_ = at_ns;
    }
  });
}

std::optional<std::int64_t> LinkTap::last_bridge_heartbeat_ns() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return last_bridge_heartbeat_ns_;
}

double LinkTap::rate_hz(std::uint32_t message_id, std::int64_t from_ns, std::int64_t to_ns) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto found = arrivals_.find(message_id);
  if (found == arrivals_.end() || to_ns <= from_ns) return 0.0;
  std::size_t count = 0;
  for (const std::int64_t at : found->second) count += at >= from_ns && at < to_ns ? 1 : 0;
  return static_cast<double>(count) / clock::ns_to_s(to_ns - from_ns);
}

std::size_t LinkTap::frames_from_firmware(std::uint32_t message_id) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto found = arrivals_.find(message_id);
  return found == arrivals_.end() ? 0 : found->second.size();
}

std::vector<Timed<mav::CommandAck>> LinkTap::acks() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return acks_;
}

std::vector<Timed<mav::CommandLong>> LinkTap::commands() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return commands_;
}

std::optional<Timed<mav::SetAttitudeTarget>> LinkTap::last_setpoint() const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (setpoint_log_.empty()) return std::nullopt;
  return setpoint_log_.back();
}

std::uint64_t LinkTap::setpoints() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return setpoint_log_.size();
}

namespace {
template <typename T>
std::vector<Timed<T>> since(const std::vector<Timed<T>>& log, std::int64_t since_ns) {
  std::vector<Timed<T>> out;
  for (const auto& t : log) {
    if (t.at_ns >= since_ns) out.push_back(t);
  }
  return out;
}
}  // namespace

std::vector<Timed<mav::SetAttitudeTarget>> LinkTap::setpoints_since(std::int64_t since_ns) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return since(setpoint_log_, since_ns);
}

std::vector<Timed<mav::AttitudeTarget>> LinkTap::attitude_targets_since(
    std::int64_t since_ns) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return since(attitude_targets_, since_ns);
}

void LinkTap::cut(bool cut) {
  cut_ = cut;
}

}  // namespace cover::firmware
