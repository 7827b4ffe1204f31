#include "cover/ugv/mavlink_imu_source.hpp"

#include <stdexcept>
#include <thread>

#include "cover/clock/clock.hpp"
#include "cover/mavlink/connection_url.hpp"
#include "cover/mavlink/messages.hpp"

namespace cover::ugv {

namespace {

constexpr double kStandardGravity_m_s2 = 9.80665;  // MAVLink's mG
// Bounds one read's draining of a busy link (a 200 Hz IMU brings one frame per datagram).
constexpr int kMaxDrainReads = 256;

Eigen::Vector3d frd_to_flu(double x, double y, double z) {
  return {x, -y, -z};
}

}  // namespace

std::optional<MavlinkStamp> parse_mavlink_stamp(const std::string& text) {
  if (text == "autopilot") return MavlinkStamp::Autopilot;
  if (text == "receive") return MavlinkStamp::Receive;
  return std::nullopt;
}

MavlinkImuSource::MavlinkImuSource(const std::string& url, MavlinkStamp stamp)
    : url_(url), stamp_(stamp), link_(mavlink::make_link(mavlink::ConnectionUrl::parse(url))) {
  if (!link_->open()) {
    throw std::runtime_error("cannot open MAVLink link " + url + ": " + link_->last_error());
  }
}

std::size_t MavlinkImuSource::read(std::vector<ImuSample>& out, std::chrono::milliseconds timeout) {
  out.clear();
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (out.empty()) {
    const auto now = std::chrono::steady_clock::now();
    if (now >= deadline) break;
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - now);
    if (!link_->is_open()) {
      reopen_if_due();
      if (!link_->is_open()) {
        std::this_thread::sleep_for(std::min(left, kReopenInterval));
        continue;
      }
    }
    read_bytes(std::max(left, std::chrono::milliseconds(1)), out);
  }
  return out.size();
}

// One blocking read, then whatever else is already there.
void MavlinkImuSource::read_bytes(std::chrono::milliseconds timeout, std::vector<ImuSample>& out) {
  std::size_t n = link_->read(buffer_.data(), buffer_.size(), timeout);
  for (int reads = 0; n > 0 && reads < kMaxDrainReads; ++reads) {
    receive_stamp_s_ = clock::system_s();
    parser_.feed(buffer_.data(), n, [&](const mavlink::Frame& frame) { on_frame(frame, out); });
    n = link_->read(buffer_.data(), buffer_.size(), std::chrono::milliseconds(0));
  }
}

void MavlinkImuSource::reopen_if_due() {
  const auto now = std::chrono::steady_clock::now();
  if (now < next_reopen_) return;
  next_reopen_ = now + kReopenInterval;
  if (link_->open()) parser_.reset();  // a partial frame from before the failure is gone
}

bool MavlinkImuSource::from_imu_system(const mavlink::Frame& frame) {
  if (!imu_system_) imu_system_ = frame.system_id;
  return *imu_system_ == frame.system_id;
}

void MavlinkImuSource::on_frame(const mavlink::Frame& frame, std::vector<ImuSample>& out) {
  if (const auto imu = mavlink::decode<mavlink::HighresImu>(frame)) {
    if (imu->id != 0 || !from_imu_system(frame)) return;
    highres_seen_ = true;
    ImuSample sample;
    sample.stamp_s = stamp_ == MavlinkStamp::Autopilot
                         ? clock::ns_to_s(static_cast<std::int64_t>(imu->time_usec) * 1000)
                         : receive_stamp_s_;
    sample.specific_force_m_s2 = frd_to_flu(imu->xacc, imu->yacc, imu->zacc);
    sample.angular_velocity_rad_s = frd_to_flu(imu->xgyro, imu->ygyro, imu->zgyro);
    deliver(sample, out);
    return;
  }
  if (const auto imu = mavlink::decode<mavlink::ScaledImu>(frame)) {
    if (highres_seen_ || !from_imu_system(frame)) return;  // HIGHRES_IMU is better
    const double mg = kStandardGravity_m_s2 * 1e-3;
    ImuSample sample;
    sample.stamp_s = stamp_ == MavlinkStamp::Autopilot
                         ? clock::ns_to_s(static_cast<std::int64_t>(imu->time_boot_ms) * 1'000'000)
                         : receive_stamp_s_;
    sample.specific_force_m_s2 = mg * frd_to_flu(imu->xacc, imu->yacc, imu->zacc);
    sample.angular_velocity_rad_s = 1e-3 * frd_to_flu(imu->xgyro, imu->ygyro, imu->zgyro);
    deliver(sample, out);
  }
}

void MavlinkImuSource::deliver(ImuSample sample, std::vector<ImuSample>& out) {
  if (last_stamp_s_ && sample.stamp_s == *last_stamp_s_) {
    ++repeats_;
    return;
  }
  if (!last_stamp_s_ || sample.stamp_s > *last_stamp_s_) last_stamp_s_ = sample.stamp_s;
  out.push_back(sample);
}

}  // namespace cover::ugv
