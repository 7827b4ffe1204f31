#pragma once

#include <array>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/uav/uav_io.hpp"
#include "cover/wire/intake.hpp"

namespace cover::uav_agent {

// The loop's inputs from DDS: the latest relative state and UGV IMU per UGV the task
// names (subscribed when a task is accepted). Every sample passes the intake checks
// (wire/intake.hpp) first: one that fails is counted, logged and dropped, and the loop
// keeps the last accepted one (which ages into the failsafe ladder's stale input).
class DdsUavInputs : public uav::UavInputs {
 public:
  DdsUavInputs(dds::Participant& participant, std::uint32_t uav_id, int ugv_count,
               wire::IntakeLimits limits = {});

  // The clock the next pulls are checked against (future stamps); call before each step.
  void set_now(double now_s);

  // Subscribes to the relative states and IMU of `ugvs`, the UGVs a task just accepted
  // names (each reader made once, kept afterwards); until the next call they are the UGVs
  // wait_for_stamps awaits.
  void subscribe(const std::vector<int>& ugvs);

  bool relative_state(int ugv, mission::RelativeMeasurement& out) override;
  bool ugv_imu(int ugv, mission::UgvImuMeasurement& out) override;

  // Stamps of the newest samples received for `ugv`, ns (-1: none), for lockstep waits.
  std::int64_t relative_stamp_ns(int ugv) const;
  std::int64_t imu_stamp_ns(int ugv) const;
  // Blocks until every UGV of the last subscribe() has a relative state stamped >=
  // relative_ns and an IMU sample stamped >= imu_ns (a stamp < 0: that input is not
  // awaited), woken by the readers' callbacks as samples arrive; false at `deadline`.
  bool wait_for_stamps(std::int64_t relative_ns, std::int64_t imu_ns,
                       std::chrono::steady_clock::time_point deadline) const;
  // The first input of a subscribed UGV without a matched writer, as a line for the log
  // ("no publisher of ..."); nullopt when every one has its writer.
  std::optional<std::string> missing_writer() const;
  // The reference UGV's relative-state reader: realtime mode steps on its fresh samples.
  dds::Reader<msg::RelativeState>* relative_reader(int ugv);

  // Samples refused so far, by reason.
  wire::RejectionCounts rejections() const;

 private:
  struct UgvReaders {
    wire::SampleSlot<msg::RelativeState> state_slot;
    wire::SampleSlot<msg::UgvImu> imu_slot;
    std::string state_topic;
    std::string imu_topic;
    dds::Reader<msg::RelativeState> state;  // last: their callbacks fill the slots
    dds::Reader<msg::UgvImu> imu;
  };
  // What wait_for_stamps waits for, while it waits.
  struct Awaited {
    std::int64_t relative_ns = -1;
    std::int64_t imu_ns = -1;
  };
  template <typename T>
  std::optional<T> take_accepted(wire::SampleSlot<T>& slot, const std::string& topic);
  void reject(wire::Rejection reason, const std::string& topic);  // mutex_ held
  bool stamps_arrived(const Awaited& awaited) const;              // mutex_ held
  // After a sample was offered (mutex_ held): whether it completes what a waiter awaits. The
  // waiter is woken once per tick, not once per sample (4 IMU samples and 2 relative states
  // in a lockstep tick of Scenario 2), each wake-up a context switch for nothing.
  bool completes_wait() const { return awaited_ && stamps_arrived(*awaited_); }

  dds::Participant& participant_;
  std::uint32_t uav_id_;
  wire::IntakeLimits limits_;
  mutable std::mutex mutex_;                 // the slots, the clock and the counts
  mutable std::condition_variable arrived_;  // what wait_for_stamps awaits has arrived
  mutable std::optional<Awaited> awaited_;
  std::optional<double> now_s_;
  wire::RejectionCounts rejections_;
  std::vector<std::unique_ptr<UgvReaders>> readers_;  // by UGV id; null: not subscribed
  std::vector<int> task_ugvs_;  // the last subscribe()'s: what wait_for_stamps awaits
};

// The loop's command to DDS: this step's command, then its trace (the vehicle waits for
// the command; a lockstep simulator waits for both before it ends the UAV's tick).
class DdsCommandOutput : public uav::CommandOutput {
 public:
  DdsCommandOutput(dds::Participant& participant, std::uint32_t uav_id);
  void write(const uav::StepOutput& step) override;
  // The last step's trace and command once more, unchanged (a lockstep answer that was
  // lost); nothing before the first step.
  void write_again();

 private:
  dds::Writer<msg::ControlTrace> trace_;
  dds::Writer<msg::UavCommand> command_;
  std::optional<msg::ControlTrace> last_trace_;
  std::optional<msg::UavCommand> last_command_;
  std::uint32_t seq_ = 0;
};

}  // namespace cover::uav_agent
