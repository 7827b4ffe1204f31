#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cover/mocap/body_filter.hpp"
#include "cover/mocap/frame_assembler.hpp"
#include "cover/mocap/relay_params.hpp"
#include "cover/vocabulary/relative_state.hpp"

namespace cover::mocap {

// The relative state of UAV `uav` in G_`ugv` at one capture time.
struct RelativeOutput {
  int uav = 0;
  int ugv = 0;
  std::int64_t stamp_ns = 0;   // on our clock
  model::RelativeState state;  // stamp_s = stamp_ns in s
  bool valid = false;
  double position_std_m = 0.0;
};

struct EstimatorStats {
  std::uint64_t frames = 0;
  std::uint64_t jumps = 0;     // measurements rejected by the gate
  std::uint64_t restarts = 0;  // filters started again (after a loss or a lasting jump)
  std::uint64_t invalid_outputs = 0;
};

// The body table and its filters; every frame yields one output per (UAV, UGV) pair.
// Positions and velocities from per-body constant-velocity Kalman filters; velocity as
// seen in G_k includes the UGV's rotation: v = R_k^T (v_u - v_k) - omega_k x p.
class RelativeEstimator {
 public:
  // Bodies in the order of params.bodies (the frame's order).
  explicit RelativeEstimator(const RelayParams& params);

  // `frame` in the server's frame and units already converted (WorldPose); `stamp_ns` is
  // its capture time on our clock. Overwrites `out` (one entry per pair, sized once).
  void on_frame(const Frame& frame, std::int64_t stamp_ns, std::vector<RelativeOutput>& out);
  std::size_t pair_count() const { return pairs_.size(); }
  // The (uav, ugv) ids of the outputs, in their order.
  std::vector<std::pair<int, int>> pair_ids() const;
  const EstimatorStats& stats() const { return stats_; }

 private:
  struct Pair {
    int uav_body;  // index into bodies
    int ugv_body;
    int uav;
    int ugv;
    bool was_valid = false;
    bool ever = false;
  };
  RelativeOutput relative(const Pair& pair, std::int64_t server_ns, std::int64_t stamp_ns) const;
  void note_body(std::size_t body, BodyFilter::Update update, const BodySample& sample,
                 std::int64_t server_ns);
  std::string why_invalid(const Pair& pair, std::int64_t server_ns) const;

  RelayParams params_;
  std::vector<BodyFilter> filters_;
  std::vector<bool> lost_logged_;
  std::vector<Pair> pairs_;
  EstimatorStats stats_;
};

}  // namespace cover::mocap
