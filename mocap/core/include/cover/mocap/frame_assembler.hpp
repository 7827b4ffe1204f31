#pragma once

#include <cstdint>
#include <vector>

#include "cover/mocap/frame_convention.hpp"

namespace cover::mocap {

// One body in a mocap frame: measured (valid) or reported lost by the server.
struct BodySample {
  bool reported = false;
  bool valid = false;
  WorldPose pose;
};

// A complete mocap frame: every body's sample at one capture time (server clock).
struct Frame {
  std::int64_t server_ns = 0;
  std::int64_t first_arrival_ns = 0;  // our monotonic clock, when its first message came
  std::vector<BodySample> bodies;
};

// Gathers a frame's messages (one per body, same timestamp) into a frame. A frame is
// complete when every body has reported, when a later timestamp arrives (its missing bodies
// are missing), or `timeout_ns` after its first message (the app calls poll()).
class FrameAssembler {
 public:
  FrameAssembler(std::size_t body_count, std::int64_t timeout_ns);

  // Returns true when a frame is complete (then take it with frame()); a body's sample of
  // a newer timestamp completes the open frame and opens the next one, which `pending()`
  // then reports.
  bool add(int body, std::int64_t server_ns, std::int64_t arrival_ns, const BodySample& sample);
  bool poll(std::int64_t now_ns);
  const Frame& frame() const { return done_; }
  bool pending() const { return open_; }
  // The last add() was a message of the frame completed last, sent again (the simulator
  // does, when a lockstep tick is published again): its outputs may be written again.
  bool repeat() const { return repeat_; }
  std::uint64_t late_samples() const { return late_; }

 private:
  void open(std::int64_t server_ns, std::int64_t arrival_ns);
  void complete();

  std::int64_t timeout_ns_;
  Frame current_;
  Frame done_;
  bool open_ = false;
  std::size_t reported_ = 0;
  std::int64_t last_done_ns_ = INT64_MIN;
  std::uint64_t late_ = 0;
  bool carry_complete_ = false;
  bool repeat_ = false;
};

}  // namespace cover::mocap
