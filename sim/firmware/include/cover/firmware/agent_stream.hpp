#pragma once
// The UAV agent's side of a firmware run: UavCommand samples on cover/uav/0/cmd at 100 Hz
// from a thread, as cover-uav-agent publishes them (stamped with the host's clock: the
// bridge runs --clock system), each computed by the flight the run chooses (a policy,
// called on that thread). The run can make the agent fall silent, as a crashed agent does.
#include <pthread.h>
#include <sched.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>

#include "cover/clock/clock.hpp"
#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"

namespace cover::firmware {

// One command: collective thrust per unit mass and body rates, FLU, as the agent's.
struct AgentSetpoint {
  double thrust_m_s2 = 0.0;
  double roll_rate = 0.0;   // rad/s about x forward
  double pitch_rate = 0.0;  // rad/s about y left
  double yaw_rate = 0.0;    // rad/s about z up
  bool armed = false;       // false: motors off (the agent's stream while it has no task)
};

class AgentStream {
 public:
  using Policy = std::function<AgentSetpoint()>;

  // `priority` > 0: the agent's thread runs SCHED_FIFO at it (as cover-uav-agent under the
  // launch files), when the system allows it.
  AgentStream(dds::Participant& participant, Policy policy, int priority = 0)
      : writer_(participant.make_writer(dds::topics::uav_command(0))),
        policy_(std::move(policy)),
        thread_([this, priority] {
          if (priority > 0) {
            sched_param param{};
            param.sched_priority = priority;
            pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);  // refused: default policy
          }
          run();
        }) {}
  ~AgentStream() { fall_silent(); }
  AgentStream(const AgentStream&) = delete;
  AgentStream& operator=(const AgentStream&) = delete;

  // From the next command on, the agent flies `policy`.
  void fly(Policy policy) {
    std::lock_guard<std::mutex> lock(mutex_);
    policy_ = std::move(policy);
  }
  // Stops publishing (the thread ends); the monotonic time of the last command written.
  std::int64_t fall_silent() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
    return last_written_ns_;
  }
  std::uint32_t written() const { return seq_; }

 private:
  void run() {
    auto next = std::chrono::steady_clock::now();
    while (!stop_) {
      AgentSetpoint s;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        s = policy_();
      }
      msg::UavCommand c;
      c.uav_id = 0;
      c.stamp_ns = clock::system_ns();
      c.seq = seq_ + 1;
      c.thrust_m_s2 = s.thrust_m_s2;
      c.body_rates_rad_s.x = s.roll_rate;
      c.body_rates_rad_s.y = s.pitch_rate;
      c.body_rates_rad_s.z = s.yaw_rate;
      c.armed = s.armed;
      c.measurement_stamp_ns = c.stamp_ns;
      writer_.write(c);
      last_written_ns_ = clock::monotonic_ns();
      seq_ = c.seq;
      next += std::chrono::milliseconds(10);  // the agent's 100 Hz, paced, not synchronising
      std::this_thread::sleep_until(next);
    }
  }

  dds::Writer<msg::UavCommand> writer_;
  std::mutex mutex_;
  Policy policy_;
  std::atomic<bool> stop_{false};
  std::atomic<std::uint32_t> seq_{0};
  std::atomic<std::int64_t> last_written_ns_{0};
  std::thread thread_;
};

}  // namespace cover::firmware
