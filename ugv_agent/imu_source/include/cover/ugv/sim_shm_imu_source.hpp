#pragma once

#include <chrono>
#include <optional>

#include <chrono>
#include <cstdint>
#include <string>

#include "cover/shm/seqlock_reader.hpp"
#include "cover/ugv/imu_source.hpp"
#include "cover/vocabulary/world_segment.hpp"

namespace cover::ugv {

// UGV k's raw IMU as the simulator publishes it: the ring imu[k] of the SharedWorld
// segment. Counts the samples it consumed and returns the newer ones; when the simulator
// got more than a ring ahead, the overwritten samples are counted as lost and reading
// resumes at the oldest sample still in the ring. Samples already in the ring when the
// source attaches are delivered (at most a ring's worth); older ones are not counted lost:
// the agent was not running then.
class SimShmImuSource : public ImuSource {
 public:
  // A waiting read blocks on the segment's sequence (shm::SeqlockReader::wait_for_write),
  // woken by the simulator's next write: the simulator in lockstep waits for the agents
  // every control period, and a poll's sleep would add its slack to every tick.
  // How often a waiting read checks that the writer still exists (a syscall or two).
  static constexpr std::chrono::milliseconds kLivenessInterval{50};

  // Waits up to `wait` for the segment to appear. Throws std::runtime_error when it does
  // not, when its layout differs, or std::invalid_argument when `ugv_index` is not in
  // 0..kMaxUgvs-1.
  SimShmImuSource(const std::string& segment_name, int ugv_index, std::chrono::milliseconds wait);

  std::size_t read(std::vector<ImuSample>& out, std::chrono::milliseconds timeout) override;
  std::string describe() const override { return "sim-shm:" + reader_.name(); }
  ImuSourceStatus status() const override { return status_; }

 private:
  // Copies the world if its sequence moved and appends UGV k's new samples; false when
  // there was nothing new (or the copy was torn: the next poll retries).
  bool take_new_samples(std::vector<ImuSample>& out);
  void check_writer();
  void remove_dead_writers_segment();

  cover::shm::SeqlockReader<cover::sim::SharedWorld> reader_;
  int ugv_index_;
  // The last copy of this UGV's ring alone: copying the whole world on every read would
  // make each UGV agent's cost grow with the fleet (N agents x N rings).
  cover::sim::ImuRing ring_{};
  // When the segment was first seen closed while its writer still ran (monotonic).
  std::optional<std::chrono::steady_clock::time_point> closed_since_;
  std::uint64_t seen_sequence_ = 0;
  // Kept across reads: a lockstep agent reads once per tick, and a check per read (two
  // system calls) would come every tick instead of every kLivenessInterval.
  std::chrono::steady_clock::time_point next_liveness_check_{};
  std::uint64_t consumed_ = 0;  // ring samples delivered (or counted lost) so far
  bool attached_ = false;       // the first read has placed consumed_
  ImuSourceStatus status_;
};

}  // namespace cover::ugv
