#include "dds_uav_io.hpp"

#include <spdlog/spdlog.h>

#include "cover/clock/clock.hpp"
#include "cover/wire/control.hpp"
#include "cover/wire/sensors.hpp"
#include "cover/wire/ugv_imu_measurement.hpp"

namespace cover::uav_agent {

DdsUavInputs::DdsUavInputs(dds::Participant& participant, std::uint32_t uav_id, int ugv_count,
                           wire::IntakeLimits limits)
    : participant_(participant),
      uav_id_(uav_id),
      limits_(limits),
      readers_(static_cast<std::size_t>(ugv_count)) {
  limits_.validate();
}

void DdsUavInputs::set_now(double now_s) {
  std::lock_guard<std::mutex> lock(mutex_);
  now_s_ = now_s;
}

void DdsUavInputs::reject(wire::Rejection reason, const std::string& topic) {
  rejections_.add(reason);
  if (rejections_.log_due(reason, clock::monotonic_ns() * 1e-9, limits_.log_period_s)) {
    spdlog::warn("dropped a sample on {}: {} (rejected so far: {})", topic, wire::to_string(reason),
                 rejections_.summary());
  }
}

void DdsUavInputs::subscribe(const std::vector<int>& ugvs) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    task_ugvs_ = ugvs;
  }
  for (const int k : ugvs) {
    if (k < 0 || k >= static_cast<int>(readers_.size()) || readers_[k]) continue;
    auto r = std::make_unique<UgvReaders>();
    UgvReaders* slots = r.get();
    const auto ugv = static_cast<std::uint32_t>(k);
    const auto state_topic = dds::topics::relative_state(uav_id_, ugv);
    const auto imu_topic = dds::topics::ugv_imu(ugv);
    r->state_topic = state_topic.name();
    r->imu_topic = imu_topic.name();
    // The waiter is notified after the lock is released: woken under it, it would block on
    // the mutex at once, a second context switch.
    r->state =
        participant_.make_reader(state_topic, [this, slots, ugv](const msg::RelativeState& s) {
          {
            std::lock_guard<std::mutex> lock(mutex_);
            const auto why = wire::check_content(s, uav_id_, ugv, limits_);
            if (why) return reject(*why, slots->state_topic);
            slots->state_slot.offer(s);
            if (!completes_wait()) return;
          }
          arrived_.notify_all();
        });
    r->imu = participant_.make_reader(imu_topic, [this, slots, ugv](const msg::UgvImu& s) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        const auto why = wire::check_content(s, ugv, limits_);
        if (why) return reject(*why, slots->imu_topic);
        slots->imu_slot.offer(s);
        if (!completes_wait()) return;
      }
      arrived_.notify_all();
    });
    std::lock_guard<std::mutex> lock(mutex_);
    readers_[k] = std::move(r);
  }
}

template <typename T>
std::optional<T> DdsUavInputs::take_accepted(wire::SampleSlot<T>& slot, const std::string& topic) {
  if (const auto why = slot.settle(now_s_, limits_)) reject(*why, topic);
  return slot.accepted();
}

bool DdsUavInputs::relative_state(int ugv, mission::RelativeMeasurement& out) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (ugv < 0 || ugv >= static_cast<int>(readers_.size()) || !readers_[ugv]) return false;
  const auto sample = take_accepted(readers_[ugv]->state_slot, readers_[ugv]->state_topic);
  if (!sample) return false;
  const auto state = wire::from_msg(*sample);
  if (!state) return false;  // the estimator lost this UGV: treated as missing
  out = *state;
  return true;
}

bool DdsUavInputs::ugv_imu(int ugv, mission::UgvImuMeasurement& out) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (ugv < 0 || ugv >= static_cast<int>(readers_.size()) || !readers_[ugv]) return false;
  const auto sample = take_accepted(readers_[ugv]->imu_slot, readers_[ugv]->imu_topic);
  if (!sample) return false;
  out = wire::from_msg(*sample);
  return true;
}

std::int64_t DdsUavInputs::relative_stamp_ns(int ugv) const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (ugv < 0 || ugv >= static_cast<int>(readers_.size()) || !readers_[ugv]) return -1;
  return readers_[ugv]->state_slot.newest_stamp_ns();
}

std::int64_t DdsUavInputs::imu_stamp_ns(int ugv) const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (ugv < 0 || ugv >= static_cast<int>(readers_.size()) || !readers_[ugv]) return -1;
  return readers_[ugv]->imu_slot.newest_stamp_ns();
}

bool DdsUavInputs::wait_for_stamps(std::int64_t relative_ns, std::int64_t imu_ns,
                                   std::chrono::steady_clock::time_point deadline) const {
  const Awaited awaited{relative_ns, imu_ns};
  std::unique_lock<std::mutex> lock(mutex_);
  awaited_ = awaited;
  const bool arrived = arrived_.wait_until(lock, deadline, [&] { return stamps_arrived(awaited); });
  awaited_.reset();
  return arrived;
}

bool DdsUavInputs::stamps_arrived(const Awaited& awaited) const {
  auto newest = [&](int ugv, bool relative) -> std::int64_t {
    if (ugv < 0 || ugv >= static_cast<int>(readers_.size()) || !readers_[ugv]) return -1;
    const UgvReaders& r = *readers_[ugv];
    return relative ? r.state_slot.newest_stamp_ns() : r.imu_slot.newest_stamp_ns();
  };
  for (const int k : task_ugvs_) {
    if (awaited.relative_ns >= 0 && newest(k, true) < awaited.relative_ns) return false;
    if (awaited.imu_ns >= 0 && newest(k, false) < awaited.imu_ns) return false;
  }
  return true;
}

wire::RejectionCounts DdsUavInputs::rejections() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return rejections_;
}

std::optional<std::string> DdsUavInputs::missing_writer() const {
  for (std::size_t k = 0; k < readers_.size(); ++k) {
    if (!readers_[k]) continue;
    if (readers_[k]->state.matched_writers() == 0) {
      return fmt::format("no publisher of cover/uav/{}/rel/{} (simulator or localisation)", uav_id_,
                         k);
    }
    if (readers_[k]->imu.matched_writers() == 0) {
      return fmt::format("no publisher of cover/ugv/{}/imu (cover-ugv-agent --id {})", k, k);
    }
  }
  return std::nullopt;
}

dds::Reader<msg::RelativeState>* DdsUavInputs::relative_reader(int ugv) {
  if (ugv < 0 || ugv >= static_cast<int>(readers_.size()) || !readers_[ugv]) return nullptr;
  return &readers_[ugv]->state;
}

DdsCommandOutput::DdsCommandOutput(dds::Participant& participant, std::uint32_t uav_id)
    : trace_(participant.make_writer(dds::topics::uav_trace(uav_id))),
      command_(participant.make_writer(dds::topics::uav_command(uav_id))) {}

void DdsCommandOutput::write(const uav::StepOutput& step) {
  last_trace_ = wire::to_trace(step.output->status, step.uav_id, step.stamp_s);
  last_command_ = wire::to_msg(step.output->command, step.uav_id, step.stamp_s,
                               step.measurement_stamp_s, seq_++);
  write_again();
}

void DdsCommandOutput::write_again() {
  if (!last_trace_ || !last_command_) return;
  // The command first: it is what the vehicle waits for (a DDS write costs 20-40 us on
  // Fast DDS); the trace is telemetry. A lockstep simulator waits for both either way.
  command_.write(*last_command_);
  trace_.write(*last_trace_);
}

}  // namespace cover::uav_agent
