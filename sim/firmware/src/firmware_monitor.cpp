#include "cover/firmware/firmware_monitor.hpp"

#include <chrono>
#include <cstring>
#include <functional>
#include <thread>

#include "cover/clock/clock.hpp"
#include "cover/firmware/sitl_ports.hpp"
#include "cover/mavlink/parameter_messages.hpp"
#include "cover/mavlink/protocol.hpp"

namespace {

// Polls `condition` every 5 ms until it holds or `timeout` passes (then one last look).
bool poll_until(const std::function<bool()>& condition, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!condition()) {
    if (std::chrono::steady_clock::now() >= deadline) return condition();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));  // a condition with a deadline
  }
  return true;
}

}  // namespace

namespace cover::firmware {
namespace {

namespace mav = cover::mavlink;
using namespace std::chrono_literals;

constexpr std::uint8_t kGcsSystem = 255;  // a ground station's conventional id
constexpr auto kReceivePoll = 10ms;
constexpr auto kHeartbeatPeriod = 1s;
constexpr auto kResendPeriod = 500ms;

template <typename T>
std::vector<Timed<T>> since(const std::vector<Timed<T>>& all, std::int64_t since_ns) {
  std::vector<Timed<T>> out;
  for (const auto& item : all) {
    if (item.at_ns >= since_ns) out.push_back(item);
  }
  return out;
}

template <typename T>
std::optional<Timed<T>> newest(const std::vector<Timed<T>>& all) {
  if (all.empty()) return std::nullopt;
  return all.back();
}

// An autopilot's HEARTBEAT, not a ground station's or a companion's (ArduPilot forwards
// the bridge's to its other links, PX4 with -f as well).
bool from_autopilot(const mav::Frame& frame, const mav::Heartbeat& heartbeat) {
  return frame.component_id == mav::mav_comp::kAutopilot1 &&
         heartbeat.autopilot != mav::mav_autopilot::kInvalid &&
         heartbeat.type != mav::mav_type::kGcs &&
         heartbeat.type != mav::mav_type::kOnboardController;
}

}  // namespace

double ParamReading::value(bool bytewise_integers) const {
  if (!bytewise_integers || type == mav::mav_param_type::kReal32) return raw;
  std::int32_t as_int = 0;
  std::memcpy(&as_int, bytes.data(), sizeof(as_int));
  return as_int;
}

std::unique_ptr<FirmwareMonitor> FirmwareMonitor::px4(int instance) {
  return std::make_unique<FirmwareMonitor>(udp_transport(px4_gcs_port(instance)));
}

std::unique_ptr<FirmwareMonitor> FirmwareMonitor::arducopter(int instance) {
  return std::make_unique<FirmwareMonitor>(tcp_transport(arducopter_gcs_port(instance)));
}

FirmwareMonitor::FirmwareMonitor(std::unique_ptr<ByteTransport> transport)
    : transport_(std::move(transport)),
      encoder_(kGcsSystem, mav::mav_comp::kMissionPlanner),
      thread_([this] { run(); }) {}

FirmwareMonitor::~FirmwareMonitor() {
  stop_ = true;
  thread_.join();
}

void FirmwareMonitor::run() {
  std::array<std::uint8_t, 4096> buffer{};
  auto next_heartbeat = std::chrono::steady_clock::now();
  while (!stop_) {
    if (std::chrono::steady_clock::now() >= next_heartbeat) {
      mav::Heartbeat heartbeat;
      heartbeat.type = mav::mav_type::kGcs;
      heartbeat.autopilot = mav::mav_autopilot::kInvalid;
      heartbeat.system_status = mav::mav_state::kActive;
      send(encoder_.encode(heartbeat));
      next_heartbeat += kHeartbeatPeriod;
    }
    std::deque<Pending> outgoing;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      outgoing.swap(outgoing_);
    }
    // The transport is used by this thread only: a TCP transport that reconnects cannot
    // race a sender.
    for (const Pending& p : outgoing) transport_->send(p.bytes.data(), p.bytes.size());
    const std::size_t n = transport_->receive(buffer.data(), buffer.size(), kReceivePoll);
    if (n == 0) continue;
    const std::int64_t at_ns = clock::monotonic_ns();
    std::lock_guard<std::mutex> lock(mutex_);
    parser_.feed(buffer.data(), n, [&](const mav::Frame& frame) { take(frame, at_ns); });
  }
}

void FirmwareMonitor::send(const mav::EncodedFrame& frame) {
  std::lock_guard<std::mutex> lock(mutex_);
  outgoing_.push_back(
      {std::vector<std::uint8_t>(frame.bytes.begin(), frame.bytes.begin() + frame.size)});
}

void FirmwareMonitor::take(const mav::Frame& frame, std::int64_t at_ns) {
  if (const auto heartbeat = mav::decode<mav::Heartbeat>(frame)) {
    if (!from_autopilot(frame, *heartbeat)) return;
    if (system_id_ == 0) system_id_ = frame.system_id;
  }
  if (system_id_ == 0 || frame.system_id != system_id_ ||
      frame.component_id != mav::mav_comp::kAutopilot1) {
    return;
  }
  arrivals_[frame.message_id].push_back(at_ns);
  switch (frame.message_id) {
    case mav::Heartbeat::kId:
      heartbeats_.push_back({at_ns, mav::Heartbeat::unpack(frame.payload.data())});
      break;
    case mav::LocalPositionNed::kId:
      positions_.push_back({at_ns, mav::LocalPositionNed::unpack(frame.payload.data())});
      break;
    case mav::AttitudeQuaternion::kId:
      attitudes_.push_back({at_ns, mav::AttitudeQuaternion::unpack(frame.payload.data())});
      break;
    case mav::HighresImu::kId:
      imus_.push_back({at_ns, mav::HighresImu::unpack(frame.payload.data())});
      break;
    case mav::AttitudeTarget::kId:
      attitude_targets_.push_back({at_ns, mav::AttitudeTarget::unpack(frame.payload.data())});
      break;
    case mav::ExtendedSysState::kId:
      extended_state_ = mav::ExtendedSysState::unpack(frame.payload.data());
      break;
    case mav::SysStatus::kId:
      sys_status_ = mav::SysStatus::unpack(frame.payload.data());
      break;
    case mav::StatusText::kId: {
      const auto text = mav::StatusText::unpack(frame.payload.data());
      texts_.push_back({at_ns, std::to_string(text.severity) + ": " + text.text_string()});
      break;
    }
    case mav::CommandAck::kId:
      acks_.push_back({at_ns, mav::CommandAck::unpack(frame.payload.data())});
      break;
    case mav::ParamValue::kId:
      params_.push_back({at_ns, mav::ParamValue::unpack(frame.payload.data())});
      break;
    default:
      break;
  }
}

bool FirmwareMonitor::connected() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return system_id_ != 0;
}

std::uint8_t FirmwareMonitor::system_id() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return system_id_;
}

std::optional<mav::Heartbeat> FirmwareMonitor::heartbeat() const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (heartbeats_.empty()) return std::nullopt;
  return heartbeats_.back().value;
}

std::vector<Timed<mav::Heartbeat>> FirmwareMonitor::heartbeats_since(std::int64_t since_ns) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return since(heartbeats_, since_ns);
}

std::optional<Timed<mav::LocalPositionNed>> FirmwareMonitor::position() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return newest(positions_);
}

std::vector<Timed<mav::LocalPositionNed>> FirmwareMonitor::positions_since(
    std::int64_t since_ns) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return since(positions_, since_ns);
}

std::optional<Timed<mav::AttitudeQuaternion>> FirmwareMonitor::attitude() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return newest(attitudes_);
}

std::vector<Timed<mav::AttitudeQuaternion>> FirmwareMonitor::attitudes_since(
    std::int64_t since_ns) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return since(attitudes_, since_ns);
}

std::vector<Timed<mav::HighresImu>> FirmwareMonitor::imus_since(std::int64_t since_ns) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return since(imus_, since_ns);
}

std::vector<Timed<mav::AttitudeTarget>> FirmwareMonitor::attitude_targets_since(
    std::int64_t since_ns) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return since(attitude_targets_, since_ns);
}

std::optional<mav::ExtendedSysState> FirmwareMonitor::extended_state() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return extended_state_;
}

std::optional<mav::SysStatus> FirmwareMonitor::sys_status() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return sys_status_;
}

std::vector<Timed<std::string>> FirmwareMonitor::texts() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return texts_;
}

double FirmwareMonitor::rate_hz(std::uint32_t message_id, std::int64_t from_ns,
                                std::int64_t to_ns) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto found = arrivals_.find(message_id);
  if (found == arrivals_.end() || to_ns <= from_ns) return 0.0;
  std::size_t count = 0;
  for (const std::int64_t at : found->second) count += at >= from_ns && at < to_ns ? 1 : 0;
  return static_cast<double>(count) / clock::ns_to_s(to_ns - from_ns);
}

std::optional<std::uint8_t> FirmwareMonitor::command(std::uint16_t command,
                                                     const std::array<float, 7>& params,
                                                     std::chrono::milliseconds timeout) {
  if (!connected()) return std::nullopt;
  mav::CommandLong message;
  message.command = command;
  message.param = params;
  message.target_system = system_id();
  message.target_component = mav::mav_comp::kAutopilot1;
  const std::int64_t asked_ns = clock::monotonic_ns();
  std::optional<std::uint8_t> result;
  auto next_send = std::chrono::steady_clock::now();
  poll_until(
      [&] {
        {
          std::lock_guard<std::mutex> lock(mutex_);
          for (const auto& ack : acks_) {
            if (ack.at_ns >= asked_ns && ack.value.command == command &&
                ack.value.result != mav::mav_result::kInProgress) {
              result = ack.value.result;
              return true;
            }
          }
        }
        if (std::chrono::steady_clock::now() >= next_send) {
          send(encoder_.encode(message));
          ++message.confirmation;
          next_send += kResendPeriod;
        }
        return false;
      },
      timeout);
  return result;
}

std::optional<std::uint8_t> FirmwareMonitor::request_stream(std::uint32_t message_id,
                                                            double rate_hz) {
  return command(mav::mav_cmd::kSetMessageInterval,
                 {static_cast<float>(message_id), static_cast<float>(1e6 / rate_hz), 0, 0, 0, 0, 0},
                 5s);
}

std::optional<std::uint8_t> FirmwareMonitor::set_mode(float custom_main, float custom_sub) {
  return command(mav::mav_cmd::kDoSetMode,
                 {static_cast<float>(mav::mav_mode_flag::kCustomModeEnabled), custom_main,
                  custom_sub, 0, 0, 0, 0},
                 5s);
}

std::optional<ParamReading> FirmwareMonitor::read_param(const std::string& name,
                                                        std::chrono::milliseconds timeout) {
  if (!connected()) return std::nullopt;
  mav::ParamRequestRead request;
  request.param_index = -1;
  request.target_system = system_id();
  request.target_component = mav::mav_comp::kAutopilot1;
  request.param_id = mav::param_id_from(name);
  return exchange_param(name, encoder_.encode(request), std::nullopt, timeout);
}

std::optional<ParamReading> FirmwareMonitor::set_param(const std::string& name, float raw,
                                                       std::uint8_t type,
                                                       std::chrono::milliseconds timeout) {
  if (!connected()) return std::nullopt;
  mav::ParamSet set;
  set.param_value = raw;
  set.param_type = type;
  set.target_system = system_id();
  set.target_component = mav::mav_comp::kAutopilot1;
  set.param_id = mav::param_id_from(name);
  return exchange_param(name, encoder_.encode(set), raw, timeout);
}

std::optional<ParamReading> FirmwareMonitor::exchange_param(const std::string& name,
                                                            const mav::EncodedFrame& request,
                                                            std::optional<float> expected_raw,
                                                            std::chrono::milliseconds timeout) {
  const std::int64_t asked_ns = clock::monotonic_ns();
  std::optional<ParamReading> reading;
  auto next_send = std::chrono::steady_clock::now();
  poll_until(
      [&] {
        if ((reading = param_since(name, asked_ns, expected_raw))) return true;
        if (std::chrono::steady_clock::now() >= next_send) {
          send(request);
          next_send += kResendPeriod;
        }
        return false;
      },
      timeout);
  return reading;
}

std::optional<ParamReading> FirmwareMonitor::param_since(const std::string& name,
                                                         std::int64_t since_ns,
                                                         std::optional<float> expected_raw) const {
  std::lock_guard<std::mutex> lock(mutex_);
  for (const auto& p : params_) {
    if (p.at_ns < since_ns || mav::param_id_string(p.value.param_id) != name) continue;
    // The same bytes: PX4's integers are bit patterns, not numbers, in the float.
    if (expected_raw && std::memcmp(&p.value.param_value, &*expected_raw, sizeof(float)) != 0) {
      continue;
    }
    ParamReading r;
    r.raw = p.value.param_value;
    r.type = p.value.param_type;
    std::memcpy(r.bytes.data(), &p.value.param_value, r.bytes.size());
    return r;
  }
  return std::nullopt;
}

}  // namespace cover::firmware
