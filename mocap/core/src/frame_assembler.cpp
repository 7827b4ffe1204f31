#include "cover/mocap/frame_assembler.hpp"

namespace cover::mocap {

FrameAssembler::FrameAssembler(std::size_t body_count, std::int64_t timeout_ns)
    : timeout_ns_(timeout_ns) {
  current_.bodies.resize(body_count);
  done_.bodies.resize(body_count);
}

void FrameAssembler::open(std::int64_t server_ns, std::int64_t arrival_ns) {
  for (auto& b : current_.bodies) b = BodySample{};
  current_.server_ns = server_ns;
  current_.first_arrival_ns = arrival_ns;
  reported_ = 0;
  open_ = true;
}

void FrameAssembler::complete() {
  done_.server_ns = current_.server_ns;
  done_.first_arrival_ns = current_.first_arrival_ns;
  done_.bodies = current_.bodies;  // same size: no allocation
  last_done_ns_ = current_.server_ns;
  open_ = false;
}

bool FrameAssembler::add(int body, std::int64_t server_ns, std::int64_t arrival_ns,
                         const BodySample& sample) {
  repeat_ = false;
  if (body < 0 || static_cast<std::size_t>(body) >= current_.bodies.size()) return false;
  // A body of the frame completed last, again: the frame repeated (not a late body).
  if (server_ns == last_done_ns_ && !(open_ && current_.server_ns > server_ns) &&
      done_.bodies[static_cast<std::size_t>(body)].reported) {
    repeat_ = true;
    return false;
  }
  if (server_ns <= last_done_ns_) {
    ++late_;  // its frame is gone
    return false;
  }
  bool completed = false;
  if (open_ && server_ns > current_.server_ns) {
    complete();
    completed = true;
  }
  if (!open_) open(server_ns, arrival_ns);
  if (server_ns < current_.server_ns) {
    ++late_;
    return completed;
  }
  BodySample& slot = current_.bodies[static_cast<std::size_t>(body)];
  if (!slot.reported) ++reported_;
  slot = sample;
  slot.reported = true;
  if (reported_ == current_.bodies.size()) {
    if (completed) {
      // Two frames complete at once: the older goes now, the newer at the next call.
      carry_complete_ = true;
      return true;
    }
    complete();
    return true;
  }
  return completed;
}

bool FrameAssembler::poll(std::int64_t now_ns) {
  if (carry_complete_) {
    carry_complete_ = false;
    complete();
    return true;
  }
  if (open_ && now_ns - current_.first_arrival_ns >= timeout_ns_) {
    complete();
    return true;
  }
  return false;
}

}  // namespace cover::mocap
