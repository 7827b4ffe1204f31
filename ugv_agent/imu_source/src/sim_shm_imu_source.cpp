#include "cover/ugv/sim_shm_imu_source.hpp"

#include <cstddef>

#include <unistd.h>

#include <algorithm>
#include <stdexcept>

#include "cover/shm/segment.hpp"
#include "cover/shm/segment_name.hpp"

namespace cover::ugv {

namespace {

using cover::sim::kImuRingCapacity;
using cover::sim::kMaxUgvs;
using cover::sim::SharedWorld;

// The ring's sample as the filter takes it (the segment stores plain arrays and a flag).
ImuSample from_raw(const cover::sim::RawImuSample& sample) {
  ImuSample s;
  s.stamp_s = sample.stamp_s;
  s.specific_force_m_s2 = sample.specific_force_m_s2.eigen();
  s.angular_velocity_rad_s = sample.angular_velocity_rad_s.eigen();
  if (sample.has_wheel_speed != 0) s.wheel_speed_m_s = sample.wheel_speed_m_s;
  return s;
}

int checked_index(int ugv_index) {
  if (ugv_index < 0 || ugv_index >= kMaxUgvs) {
    throw std::invalid_argument("UGV index " + std::to_string(ugv_index) + " is not in 0.." +
                                std::to_string(kMaxUgvs - 1));
  }
  return ugv_index;
}

}  // namespace

const char* to_string(ImuSourceState state) {
  switch (state) {
    case ImuSourceState::Ok:
      return "ok";
    case ImuSourceState::Ended:
      return "ended";
    case ImuSourceState::Gone:
      return "gone";
  }
  return "unknown";
}

SimShmImuSource::SimShmImuSource(const std::string& segment_name, int ugv_index,
                                 std::chrono::milliseconds wait)
    : reader_(cover::shm::SeqlockReader<SharedWorld>::open(
          segment_name, cover::sim::kWorldSegmentLayoutVersion, wait)),
      ugv_index_(checked_index(ugv_index)) {}

std::size_t SimShmImuSource::read(std::vector<ImuSample>& out, std::chrono::milliseconds timeout) {
  out.clear();
  const auto start = std::chrono::steady_clock::now();
  const auto give_up = start + timeout;
  while (status_.state == ImuSourceState::Ok) {
    if (take_new_samples(out)) return out.size();
    const auto now = std::chrono::steady_clock::now();
    if (now >= next_liveness_check_) {
      check_writer();
      // The writer's last samples may have landed just before it went.
      if (status_.state != ImuSourceState::Ok) take_new_samples(out);
      next_liveness_check_ = now + kLivenessInterval;
      continue;
    }
    if (now >= give_up) break;
    // Nothing new: sleep until the simulator writes (its wake-up), the next liveness check
    // or the timeout. A write that completed since the look above is read first.
    const std::uint64_t sequence = reader_.sequence();
    if (sequence == seen_sequence_ || sequence % 2 == 1) {
      reader_.wait_for_write(sequence, std::min(give_up, next_liveness_check_) - now);
    }
  }
  return out.size();
}

bool SimShmImuSource::take_new_samples(std::vector<ImuSample>& out) {
  // Looking at the sequence costs one load; the copy is only made when it moved.
  const std::uint64_t sequence = reader_.sequence();
  if (sequence == seen_sequence_ || sequence % 2 == 1) return false;
  // The world's UGV count is set when the simulator starts: the ring is read only for a
  // UGV the run has.
  std::int32_t ugv_count = 0;
  if (!reader_.read_part(offsetof(SharedWorld, ugv_count), ugv_count)) return false;
  if (ugv_count > 0 && ugv_index_ >= ugv_count) {
    status_.state = ImuSourceState::Gone;
    status_.detail = "the simulator runs " + std::to_string(ugv_count) +
                     " UGV(s): there is no UGV " + std::to_string(ugv_index_);
    return false;
  }
  const std::size_t offset = offsetof(SharedWorld, imu) +
                             static_cast<std::size_t>(ugv_index_) * sizeof(cover::sim::ImuRing);
  if (!reader_.read_part(offset, ring_)) return false;
  seen_sequence_ = reader_.last_read_sequence();
  const cover::sim::ImuRing& ring = ring_;
  const std::uint64_t capacity = kImuRingCapacity;
  const std::uint64_t oldest = ring.written > capacity ? ring.written - capacity : 0;
  if (!attached_) {
    consumed_ = oldest;
    attached_ = true;
  }
  if (consumed_ < oldest) {
    status_.lost_samples += oldest - consumed_;
    consumed_ = oldest;
  }
  for (; consumed_ < ring.written; ++consumed_) {
    out.push_back(from_raw(ring.slots[consumed_ % capacity]));
  }
  return !out.empty();
}

namespace {
constexpr std::chrono::seconds kWriterExitWait{3};
}  // namespace

void SimShmImuSource::check_writer() {
  // A simulator that ends unlinks its segment: the device closed, the source ends. One
  // that crashed leaves it behind with a dead writer pid: the device is gone.
  const bool name_exists = ::access(cover::shm::segment_path(reader_.name()).c_str(), F_OK) == 0;
  if (!name_exists) {
    // End only once the simulator's process is gone (its supervisor reaped it), so that a
    // launcher sees the simulator end the run before it sees this agent leave; bounded,
    // for a writer that closes its world and lives on.
    const auto now = std::chrono::steady_clock::now();
    if (!closed_since_) closed_since_ = now;
    if (reader_.writer_alive() && now - *closed_since_ < kWriterExitWait) return;
    status_.state = ImuSourceState::Ended;
    status_.detail = "the simulator closed segment " + reader_.name();
    return;
  }
  if (reader_.writer_alive()) return;
  status_.state = ImuSourceState::Gone;
  status_.detail = "the simulator (pid " + std::to_string(reader_.writer_pid()) +
                   ") died and left segment " + reader_.name() + " behind";
  remove_dead_writers_segment();
}

// Nobody else will: a killed simulator cannot unlink its world. Only while the name still
// holds that dead writer's segment (a new simulator may have replaced it meanwhile).
void SimShmImuSource::remove_dead_writers_segment() {
  try {
    const auto current = cover::shm::SeqlockReader<SharedWorld>::open(
        reader_.name(), cover::sim::kWorldSegmentLayoutVersion, std::chrono::milliseconds(0));
    if (current.writer_pid() != reader_.writer_pid() || current.writer_alive()) return;
  } catch (const std::exception&) {
    return;  // gone already, or not a world of ours: leave it
  }
  if (cover::shm::remove_segment(reader_.name())) status_.detail += " (removed it)";
}

}  // namespace cover::ugv
