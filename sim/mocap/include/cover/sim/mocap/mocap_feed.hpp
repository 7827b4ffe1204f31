#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <deque>
#include <random>
#include <string>
#include <vector>

#include "cover/sim/mocap/mocap_server_params.hpp"
#include "cover/sim/mocap/vrpn_server.hpp"

namespace cover::sim::mocap {

// A body's true pose in the simulator's world frame (z up, metres).
struct BodyTruth {
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  Eigen::Quaterniond attitude = Eigen::Quaterniond::Identity();
};

struct MocapFrame {
  std::int64_t capture_ns = 0;
  std::vector<WirePose> poses;  // in the server's frame and units
};

// The body names the simulator serves: ugv<k> for every UGV, then uav<u> for every UAV.
std::vector<std::string> body_names(const MocapServerParams& params, int ugv_count, int uav_count);

// A world pose (z up, m) as a server with `up_axis` and `units` streams it. y up: the
// world rotated -90 deg about x, (x, y, z) -> (x, z, -y), and each body's axes with it
// (R q R^-1: a level body reads as the identity in both conventions).
WirePose to_wire(const BodyTruth& truth, const std::string& up_axis, const std::string& units);

// Turns the world's poses into mocap frames: captures at rate_hz, adds noise and
// dropouts, releases each frame latency_s after its capture.
class MocapFeed {
 public:
  // `params` validated.
  MocapFeed(const MocapServerParams& params, std::size_t body_count);

  // Called on every simulation step at time `t_ns` with every body's truth (in the order
  // of body_names). Appends to `released` the frames due now (captured <= t_ns - latency).
  void step(std::int64_t t_ns, const std::vector<BodyTruth>& truth,
            std::vector<MocapFrame>& released);

 private:
  WirePose measure(const BodyTruth& truth);

  MocapServerParams params_;
  std::size_t body_count_;
  std::int64_t period_ns_;
  std::int64_t latency_ns_;
  std::int64_t next_capture_ns_ = 0;
  bool started_ = false;
  std::deque<MocapFrame> queue_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
  std::uniform_real_distribution<double> uniform_{0.0, 1.0};
};

}  // namespace cover::sim::mocap
