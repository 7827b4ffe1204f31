#include "dds_uav_io.hpp"

#include <spdlog/spdlog.h>

#include "cover/wire/control.hpp"
#include "cover/wire/sensors.hpp"

namespace cover::uav_agent {

DdsUavInputs::DdsUavInputs(dds::Participant& participant, std::uint32_t uav_id, int ugv_count)
    : participant_(participant), uav_id_(uav_id), readers_(static_cast<std::size_t>(ugv_count)) {}

void DdsUavInputs::subscribe(const std::vector<int>& ugvs) {
  for (const int k : ugvs) {
    if (k < 0 || k >= static_cast<int>(readers_.size()) || readers_[k]) continue;
    auto r = std::make_unique<UgvReaders>();
    const auto ugv = static_cast<std::uint32_t>(k);
    r->state = participant_.make_reader(dds::topics::relative_state(uav_id_, ugv));
    r->imu = participant_.make_reader(dds::topics::ugv_imu(ugv));
    readers_[k] = std::move(r);
  }
}

bool DdsUavInputs::relative_state(int ugv, mission::RelativeMeasurement& out) {
  if (ugv < 0 || ugv >= static_cast<int>(readers_.size()) || !readers_[ugv]) return false;
  const auto received = readers_[ugv]->state.latest();
  if (!received) return false;
  const auto state = wire::from_msg(received->sample);
  if (!state) return false;  // the estimator lost this UGV: treated as missing
  out = *state;
  return true;
}

bool DdsUavInputs::ugv_imu(int ugv, mission::UgvImuMeasurement& out) {
  if (ugv < 0 || ugv >= static_cast<int>(readers_.size()) || !readers_[ugv]) return false;
  const auto received = readers_[ugv]->imu.latest();
  if (!received) return false;
  out = wire::from_msg(received->sample);
  return true;
}

std::int64_t DdsUavInputs::relative_stamp_ns(int ugv) const {
  if (ugv < 0 || ugv >= static_cast<int>(readers_.size()) || !readers_[ugv]) return -1;
  const auto received = readers_[ugv]->state.latest();
  return received ? received->sample.stamp_ns : -1;
}

std::int64_t DdsUavInputs::imu_stamp_ns(int ugv) const {
  if (ugv < 0 || ugv >= static_cast<int>(readers_.size()) || !readers_[ugv]) return -1;
  const auto received = readers_[ugv]->imu.latest();
  return received ? received->sample.stamp_ns : -1;
}

bool DdsUavInputs::wait_for_writers(std::chrono::milliseconds timeout) const {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (std::size_t k = 0; k < readers_.size(); ++k) {
    if (!readers_[k]) continue;
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (!readers_[k]->state.wait_for_writers(1, left)) {
      spdlog::error("no publisher of cover/uav/{}/rel/{} (simulator or localisation)", uav_id_, k);
      return false;
    }
    if (!readers_[k]->imu.wait_for_writers(1, left)) {
      spdlog::error("no publisher of cover/ugv/{}/imu (cover-ugv-agent --id {})", k, k);
      return false;
    }
  }
  return true;
}

dds::Reader<msg::RelativeState>* DdsUavInputs::relative_reader(int ugv) {
  if (ugv < 0 || ugv >= static_cast<int>(readers_.size()) || !readers_[ugv]) return nullptr;
  return &readers_[ugv]->state;
}

DdsCommandOutput::DdsCommandOutput(dds::Participant& participant, std::uint32_t uav_id)
    : trace_(participant.make_writer(dds::topics::uav_trace(uav_id))),
      command_(participant.make_writer(dds::topics::uav_command(uav_id))) {}

void DdsCommandOutput::write(const uav::StepOutput& step) {
  trace_.write(wire::to_trace(step.output->status, step.uav_id, step.stamp_s));
  command_.write(wire::to_msg(step.output->command, step.uav_id, step.stamp_s,
                              step.measurement_stamp_s, seq_++));
}

}  // namespace cover::uav_agent
