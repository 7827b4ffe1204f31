// mocap/core: parameters, frames, filters, the relative state and its validity.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "cover/config/config_error.hpp"
#include "cover/mocap/body_filter.hpp"
#include "cover/mocap/frame_assembler.hpp"
#include "cover/mocap/frame_convention.hpp"
#include "cover/mocap/relative_estimator.hpp"
#include "cover/mocap/relay_params.hpp"
#include "cover/mocap/server_clock.hpp"
#include "cover/test/shipped_params.hpp"
#include "scripted_motion.hpp"

namespace {

namespace mocap = cover::mocap;
namespace motion = cover::test::mocap_motion;

mocap::RelayParams params_from(const std::string& yaml) {
  return mocap::RelayParams::from_yaml(YAML::Load(yaml), "test.yaml");
}

const char* kMinimal = "mocap: {server: 'mocap.lab:3883', bodies: {uav0: UAV_A, ugv1: Truck_2}}";

TEST(MocapParams, ServerAndBodiesAloneWork) {
  const auto p = params_from(kMinimal);
  EXPECT_EQ(p.server, "mocap.lab:3883");
  ASSERT_EQ(p.bodies.size(), 2u);
  EXPECT_EQ(p.uav_ids(), std::vector<int>{0});
  EXPECT_EQ(p.ugv_ids(), std::vector<int>{1});
  const mocap::RelayParams defaults;
  EXPECT_EQ(p.up_axis, "z");
  EXPECT_EQ(p.units, "m");
  EXPECT_EQ(p.jump_gate_m, defaults.jump_gate_m);
  EXPECT_EQ(p.filter.accel_noise_m_s2, defaults.filter.accel_noise_m_s2);
}

// Every field (RelayParams::fields) is written at its default; `server` is required, so
// the file's is an example, not a default.
TEST(MocapParams, TheShippedFileHoldsTheDefaults) {
  const std::string path = std::string(COVER_CONFIG_DIR) + "/mocap.yaml";
  mocap::RelayParams shipped = mocap::RelayParams::load_file(path);
  EXPECT_EQ(shipped.server, "127.0.0.1:3883");
  shipped.server = mocap::RelayParams{}.server;
  cover::test::expect_shipped_file_holds_defaults(shipped, path, "mocap");
}

TEST(MocapParams, ErrorsNameTheKey) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"mocap: {bodies: {uav0: A, ugv0: B}}", "server"},
      {"mocap: {server: 'h:99999', bodies: {uav0: A, ugv0: B}}", "mocap.server"},
      {"mocap: {server: h, bodies: {uav0: A}}", "mocap.bodies"},
      {"mocap: {server: h, bodies: {uav0: A, ugv0: A}}", "mocap.bodies"},
      {"mocap: {server: h, bodies: {drone0: A, ugv0: B}}", "mocap.bodies.drone0"},
      {"mocap: {server: h, up_axis: x, bodies: {uav0: A, ugv0: B}}", "mocap.up_axis"},
      {"mocap: {server: h, units: cm, bodies: {uav0: A, ugv0: B}}", "mocap.units"},
      {"mocap: {server: h, bodies: {uav0: A, ugv0: B}, filter: {acel: 1}}", "acel"},
      {"mocap: {server: h, bodies: {uav0: A, ugv0: B}, gate: 1}", "gate"},
      {"mocap: {server: h, bodies: {uav0: A, ugv0: B}, time_source: gps}",
       "test.yaml.mocap.time_source: 'gps' is not one of server, offset"},
      {"mocap: {server: h, bodies: {uav0: A, ugv0: B}, warmup_updates: 1}",
       "mocap.warmup_updates: must be in [2, 100]"},
      {"mocap: {server: h, bodies: {uav0: A, ugv0: B}, filter: {position_noise_m: 2}}",
       "mocap.filter.position_noise_m: must be in [1e-06, 1]"},
      {"mocap: {server: h, bodies: {uav0: A, ugv0: B}, backoff_min_s: 3}",
       "mocap.backoff_max_s: must be >= backoff_min_s"},
  };
  for (const auto& [yaml, key] : cases) {
    try {
      params_from(yaml);
      ADD_FAILURE() << yaml;
    } catch (const cover::config::ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  }
}

TEST(MocapFrames, YUpMillimetresBecomeZUpMetres) {
  // A y-up server in mm: world (1, 2, 3) m is (1000, 3000, -2000); a yaw of 0.5 rad about
  // world z is a rotation about the server's y.
  const mocap::WorldPose w = mocap::to_world({1000.0, 3000.0, -2000.0},
                                             {0.0, std::sin(0.25), 0.0, std::cos(0.25)}, "y", "mm");
  EXPECT_NEAR(w.position_m.x(), 1.0, 1e-12);
  EXPECT_NEAR(w.position_m.y(), 2.0, 1e-12);
  EXPECT_NEAR(w.position_m.z(), 3.0, 1e-12);
  EXPECT_NEAR(mocap::yaw_of(w.attitude), 0.5, 1e-12);
  const mocap::WorldPose z = mocap::to_world({1.0, 2.0, 3.0}, {0, 0, 0, 1}, "z", "m");
  EXPECT_EQ(z.position_m, Eigen::Vector3d(1, 2, 3));
}

TEST(MocapAssembler, CompletesOnAllBodiesANewerStampOrTheTimeout) {
  mocap::FrameAssembler a(2, 3'000'000);
  mocap::BodySample s;
  s.valid = true;
  EXPECT_FALSE(a.add(0, 100, 0, s));
  EXPECT_TRUE(a.add(1, 100, 10, s));  // both bodies
  EXPECT_EQ(a.frame().server_ns, 100);
  EXPECT_FALSE(a.add(0, 200, 20, s));
  EXPECT_TRUE(a.add(0, 300, 30, s));  // a newer stamp: 200 goes without body 1
  EXPECT_EQ(a.frame().server_ns, 200);
  EXPECT_FALSE(a.frame().bodies[1].reported);
  EXPECT_FALSE(a.poll(30 + 2'999'999));
  EXPECT_TRUE(a.poll(30 + 3'000'000));  // the timeout
  EXPECT_EQ(a.frame().server_ns, 300);
  EXPECT_FALSE(a.add(1, 300, 40, s));  // its frame is gone
  EXPECT_EQ(a.late_samples(), 1u);
  EXPECT_FALSE(a.repeat());
  EXPECT_FALSE(a.add(0, 300, 50, s));  // the frame sent again (a lockstep tick republished)
  EXPECT_TRUE(a.repeat());
  EXPECT_EQ(a.late_samples(), 1u);
}

TEST(MocapClock, OffsetIsTheSmallestDelayInTheWindow) {
  mocap::ServerClock c("offset", 1.0);
  const std::int64_t offset = 5'000'000'000;
  EXPECT_EQ(c.to_ours(0, offset + 700'000), offset + 700'000);
  EXPECT_EQ(c.to_ours(10'000'000, offset + 10'200'000), offset + 10'000'000 + 200'000);
  EXPECT_EQ(c.to_ours(20'000'000, offset + 20'900'000), offset + 20'000'000 + 200'000);
  // Past the window the old minimum is forgotten.
  EXPECT_EQ(c.to_ours(2'000'000'000, offset + 2'000'400'000), offset + 2'000'000'000 + 400'000);
  mocap::ServerClock same("server", 1.0);
  EXPECT_EQ(same.to_ours(123, 456), 123);
}

// Feeds the scripted motion at 100 Hz to an estimator of uav0 / ugv0.
struct Scripted {
  mocap::RelayParams params = params_from("mocap: {server: h, bodies: {uav0: U, ugv0: G}}");
  mocap::RelativeEstimator estimator{params};
  std::vector<mocap::RelativeOutput> out;

  void frame(double t, bool uav_present = true, const Eigen::Vector3d& uav_offset = {0, 0, 0}) {
    mocap::Frame f;
    f.server_ns = std::llround(t * 1e9);
    f.bodies.resize(2);
    const auto u = motion::uav(t);
    const auto g = motion::ugv(t);
    f.bodies[0] = {uav_present, uav_present, {u.position_m + uav_offset, u.attitude}};
    f.bodies[1] = {true, true, {g.position_m, g.attitude}};
    estimator.on_frame(f, f.server_ns, out);
  }
};

double p99(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(0.99 * (v.size() - 1))];
}

TEST(MocapEstimator, ScriptedMotionWithinTheIssueAccuracy) {
  Scripted s;
  std::vector<double> position_error, velocity_error, attitude_error;
  for (int i = 0; i <= 1000; ++i) {
    const double t = i * 0.01;
    s.frame(t);
    ASSERT_EQ(s.out.size(), 1u);
    const auto& o = s.out[0];
    if (i < 10) continue;  // warm-up: the velocity needs a few frames
    ASSERT_TRUE(o.valid) << t;
    position_error.push_back((o.state.position_m - motion::uav_in_ugv(t)).norm());
    velocity_error.push_back((o.state.velocity_m_s - motion::uav_velocity_in_ugv(t)).norm());
    attitude_error.push_back(o.state.attitude.angularDistance(motion::uav_attitude_in_ugv(t)));
  }
  EXPECT_LE(p99(position_error), 0.005);
  EXPECT_LE(p99(velocity_error), 0.05);
  EXPECT_LE(p99(attitude_error), 0.01);
  std::printf(
      "scripted, no noise: position p99 %.2f mm, velocity p99 %.1f mm/s, attitude %.2f mrad\n",
      p99(position_error) * 1e3, p99(velocity_error) * 1e3, p99(attitude_error) * 1e3);
}

TEST(MocapEstimator, ABodyLostForAWhileIsInvalidThenValidAgain) {
  Scripted s;
  std::vector<bool> valid;
  for (int i = 0; i <= 200; ++i) {
    const double t = i * 0.01;
    s.frame(t, !(t >= 0.995 && t < 1.295));  // 0.3 s gap
    valid.push_back(s.out[0].valid);
    EXPECT_TRUE(std::isfinite(s.out[0].state.position_m.norm()));
  }
  EXPECT_TRUE(valid[99]);
  EXPECT_TRUE(valid[104]);   // 40 ms: coasted
  EXPECT_FALSE(valid[106]);  // 60 ms > lost_after_s
  EXPECT_FALSE(valid[129]);
  EXPECT_TRUE(valid[132]);  // back (from 1.30 s) and warmed up (3 frames)
  EXPECT_EQ(s.estimator.stats().restarts, 1u);
}

TEST(MocapEstimator, AJumpIsRejectedThenALastingOneRestarts) {
  Scripted s;
  for (int i = 0; i <= 50; ++i) s.frame(i * 0.01);
  ASSERT_TRUE(s.out[0].valid);
  s.frame(0.51, true, {1.0, 0.0, 0.0});  // one wild sample
  EXPECT_FALSE(s.out[0].valid);
  EXPECT_NEAR((s.out[0].state.position_m - motion::uav_in_ugv(0.51)).norm(), 0.0, 0.005);
  s.frame(0.52);
  EXPECT_TRUE(s.out[0].valid);
  EXPECT_EQ(s.estimator.stats().jumps, 1u);
  // The body really moved by 1 m: rejected for jump_reset_s, then followed.
  int i = 53;
  for (; i < 53 + 30; ++i) {
    s.frame(i * 0.01, true, {1.0, 0.0, 0.0});
    if (s.out[0].valid) break;
  }
  EXPECT_GE((i - 53) * 0.01, s.params.jump_reset_s - 1e-9);
  EXPECT_LE((i - 53) * 0.01, s.params.jump_reset_s + 0.05);
}

TEST(MocapEstimator, VelocityDelayOfTheFilter) {
  // A body accelerating at 2 m/s^2 along x: the filter's velocity lags the truth by a
  // constant; that lag over the acceleration is the filter's delay (docs/mocap.md).
  mocap::RelayParams p = params_from("mocap: {server: h, bodies: {uav0: U, ugv0: G}}");
  mocap::BodyFilter f(p);
  double lag_s = 0.0;
  for (int i = 0; i <= 300; ++i) {
    const double t = i * 0.01;
    mocap::WorldPose pose;
    pose.position_m = {t * t, 0.0, 0.0};
    f.measure(std::llround(t * 1e9), pose);
    lag_s = (2.0 * t - f.velocity().x()) / 2.0;
  }
  std::printf("velocity delay %.1f ms at 100 Hz (accel noise %.1f m/s^2, position noise %.4f m)\n",
              lag_s * 1e3, p.filter.accel_noise_m_s2, p.filter.position_noise_m);
  EXPECT_GT(lag_s, 0.0);
  EXPECT_LT(lag_s, 0.02);
}

}  // namespace
