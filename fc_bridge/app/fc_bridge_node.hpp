#pragma once

#include <atomic>
#include <chrono>

#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "bridge_clock.hpp"
#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/fc_bridge/bridge.hpp"
#include "cover/mavlink/link.hpp"
#include "cover/mavlink/parser.hpp"
#include "link_keeper.hpp"
#include "lockstep_steps.hpp"

namespace cover::fc_bridge {

struct NodeOptions {
  std::uint32_t uav_id = 0;
  BridgeConfig bridge;
  sim_clock::ClockMode clock = sim_clock::ClockMode::System;
  // Lockstep: COVER's simulated autopilot closes each step's frames with a HIGHRES_IMU
  // stamped with the step, which each command waits for (repeatable runs). A real firmware
  // (SITL) in a lockstep world has no such contract: the bridge keeps the simulator's ticks
  // as its time, takes frames as they come, and writes its state after each command.
  bool step_frames = true;
  mavlink::ParserOptions parser;
};

// cover-fc-bridge as a process: the Bridge (core) between the DDS topics and the MAVLink
// link. Three threads meet in it, serialised by one mutex held only for the Bridge's calls
// and the writes to the link:
//  - the DDS receive thread of cover/uav/U/cmd: each command becomes a SET_ATTITUDE_TARGET
//    written at once (the latency path: no allocation, no log line per sample);
//  - the link's reader thread: the autopilot's frames;
//  - run()'s housekeeping loop, 50 Hz (lockstep: every simulator tick): resends,
//    failsafe, heartbeat, cover/uav/U/fc at state_rate_hz and on every change (lockstep:
//    with each step's frames, stamped with the step, see LockstepSteps).
// Operator requests (cover/fc/request) are answered on cover/fc/reply.
class FcBridgeNode {
 public:
  FcBridgeNode(dds::Participant& participant, NodeOptions options,
               std::unique_ptr<mavlink::Link> link);
  ~FcBridgeNode();

  // Opens the link (false: it could not; the caller decides whether that is fatal).
  bool start();
  // Until SIGINT / SIGTERM.
  void run();

 private:
  // What a Bridge call produced for the log and the operators, taken out under the lock
  // and reported after it (empty, and allocation-free, in the steady state).
  struct Events {
    std::vector<Notice> notices;
    std::vector<OperatorReply> replies;
    bool empty() const { return notices.empty() && replies.empty(); }
  };

  void on_command(const msg::UavCommand& command);
  void on_request(const msg::FcRequest& request);
  void on_frame(const mavlink::Frame& frame, const mavlink::ParserStats& stats);
  void housekeeping(double now_s);
  std::chrono::milliseconds next_wait() const;
  bool lockstep() const { return options_.clock == sim_clock::ClockMode::Lockstep; }
  // Lockstep with COVER's simulated autopilot: each step's frames, closed by HIGHRES_IMU.
  bool step_frames() const { return lockstep() && options_.step_frames; }
  void write_locked(const std::vector<mavlink::EncodedFrame>& frames);
  void take_events_locked(Events& events);
  void report(Events& events);
  void reply(const std::string& request_id, msg::FcCommandResult result,
             const std::string& message);
  bool seen_before(const std::string& request_id);
  // Lockstep (mutex_ held).
  void await_step_frames_locked(std::unique_lock<std::mutex>& lock, double tick_s);
  void close_step_locked(const mavlink::Frame& frame);
  // cover/uav/U/fc at state_rate_hz and on a change; `every_step`: whatever the pace. From
  // one thread at a time: the housekeeping thread in realtime, under mutex_ in lockstep.
  void write_state(const FcStatus& status, double stamp_s, bool every_step);

  NodeOptions options_;
  BridgeClock clock_;
  std::mutex mutex_;  // the Bridge and the link's write side
  Bridge bridge_;
  std::uint64_t write_failures_ = 0;
  std::atomic<double> last_command_tick_s_{-1.0};  // bridge time of the last agent command
  LockstepSteps steps_;                            // under mutex_
  bool step_frames_late_logged_ = false;           // under mutex_
  dds::Writer<msg::FcState> state_writer_;
  dds::Writer<msg::FcReply> reply_writer_;
  std::optional<msg::FcState> last_state_;
  double next_state_monotonic_s_ = 0.0;
  std::deque<std::string> recent_requests_;      // duplicates (a station sending again) skipped
  LinkKeeper link_;                              // after what its thread's callback uses
  dds::Reader<msg::UavCommand> command_reader_;  // last: their callbacks use the above
  dds::Reader<msg::FcRequest> request_reader_;
};

}  // namespace cover::fc_bridge
