// cover-fc-bridge against an independent MAVLink implementation: the fake autopilot of
// tests/mavlink/peer/fake_autopilot.js (node-mavlink) checks every frame the bridge
// writes and answers its commands as PX4 / ArduPilot would. Skips only when Node is absent.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "cover/dds/domain_claim.hpp"
#include "process_support.hpp"

namespace cover::fc_bridge {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using test::wait_until;

const fs::path kPeerDir = COVER_MAVLINK_PEER_DIR;
constexpr int kSys = 42;
constexpr int kRunSeconds = 7;  // 1 s of stream, OFFBOARD, a HEARTBEAT to see it, arm

class FcBridgePeer : public ::testing::TestWithParam<const char*> {
 protected:
  void SetUp() override {
    node_ = test::find_node();
    if (node_.empty()) {
      GTEST_SKIP() << "node is not installed: the node-mavlink fake autopilot needs Node >= 18";
    }
    ASSERT_TRUE(fs::exists(kPeerDir / "node_modules" / "node-mavlink" / "package.json"))
        << "node-mavlink is not installed in " << kPeerDir
        << ": run scripts/setup (npm ci --prefix tests/mavlink/peer)";
  }
  std::string node_;
};

const nlohmann::json* find_command(const nlohmann::json& commands, int command, double param,
                                   int param_index, std::size_t* index) {
  for (std::size_t i = 0; i < commands.size(); ++i) {
    const auto& c = commands[i];
    const char* key = param_index == 1 ? "param1" : "param2";
    if (c["command"] == command && c[key].get<double>() == param) {
      *index = i;
      return &c;
    }
  }
  return nullptr;
}

TEST_P(FcBridgePeer, StreamsThenOffboardThenArmsWithFramesTheFakeAccepts) {
  const std::string autopilot = GetParam();
  const bool px4 = autopilot == "px4";
  const auto claim = dds::DomainClaim::claim_any(200, 209);
  const int port = test::free_udp_port();
  process::SpawnOptions fake_options;
  fake_options.capture_stdout = true;
  fake_options.log_file = cover::test::scratch_path("fake_autopilot.log");
  process::ChildProcess fake(
      {node_, (kPeerDir / "fake_autopilot.js").string(), "--port", std::to_string(port),
       "--autopilot", autopilot, "--sysid", std::to_string(kSys), "--duration-s",
       std::to_string(kRunSeconds * cover::test::whole_time_scale())},
      fake_options);
  auto bridge = test::start_bridge(claim.domain(), {"--autopilot", autopilot, "--url",
                                                    "udpout://127.0.0.1:" + std::to_string(port),
                                                    "--auto-arm", "--clock", "system"});
  dds::Participant participant(test::on_domain(claim.domain()));
  auto fc = participant.make_reader(dds::topics::fc_state(0));
  test::AgentStream agent(participant);

  EXPECT_TRUE(wait_until([&] { return fc.latest() && fc.latest()->sample.offboard_ready; },
                         std::chrono::seconds(kRunSeconds)))
      << "the bridge never reported the autopilot armed in offboard";
  const auto line = fake.read_line(test::scaled(std::chrono::seconds(kRunSeconds + 10)));
  ASSERT_TRUE(line) << "the fake autopilot printed no result";
  const auto result = nlohmann::json::parse(*line);
  SCOPED_TRACE(result.dump());

  EXPECT_EQ(result["bad_frame_count"], 0);
  EXPECT_EQ(result["crc_errors"], 0);
  EXPECT_GT(result["setpoints"].get<int>(), 200);
  EXPECT_EQ(result["first_setpoint_before_offboard"], true);
  const auto& commands = result["commands"];
  std::size_t offboard_at = 0;
  std::size_t arm_at = 0;
  const auto* offboard = find_command(commands, 176, px4 ? 6 : 20, 2, &offboard_at);
  const auto* arm = find_command(commands, 400, 1, 1, &arm_at);
  ASSERT_NE(offboard, nullptr) << "no OFFBOARD / GUIDED_NOGPS request";
  ASSERT_NE(arm, nullptr) << "no arm request (--auto-arm)";
  EXPECT_EQ((*offboard)["result"], 0) << "requested before the stream was long enough";
  // Before the mode: only the stream requests (SET_MESSAGE_INTERVAL), as node-mavlink reads
  // them: HIGHRES_IMU (105) every 10 ms, EXTENDED_SYS_STATE (245) every 200 ms.
  for (std::size_t i = 0; i < offboard_at; ++i) {
    EXPECT_EQ(commands[i]["command"], 511) << "the first mode or arm command must be the mode";
  }
  std::size_t at = 0;
  const auto* imu_stream = find_command(commands, 511, 105, 1, &at);
  ASSERT_NE(imu_stream, nullptr) << "HIGHRES_IMU was not asked for";
  EXPECT_EQ((*imu_stream)["param2"].get<double>(), 10000.0);
  EXPECT_EQ((*imu_stream)["result"], 0);
  const auto* landed_stream = find_command(commands, 511, 245, 1, &at);
  ASSERT_NE(landed_stream, nullptr) << "EXTENDED_SYS_STATE was not asked for";
  EXPECT_EQ((*landed_stream)["param2"].get<double>(), 200000.0);
  EXPECT_GT(arm_at, offboard_at);
  EXPECT_EQ((*arm)["result"], 0);
  EXPECT_EQ(result["armed"], true);
  EXPECT_EQ(result["mode"].get<long>(), px4 ? (6L << 16) : 20L);
  // FLU (0.1, 0.2, 0.3) as FRD (0.1, -0.2, -0.3).
  EXPECT_GT(result["rate_sums"]["roll"].get<double>(), 0.0);
  EXPECT_LT(result["rate_sums"]["pitch"].get<double>(), 0.0);
  EXPECT_LT(result["rate_sums"]["yaw"].get<double>(), 0.0);
  const auto& last = result["last_setpoint"];
  ASSERT_TRUE(last.is_object());
  EXPECT_NEAR(last["thrust"].get<double>(), 0.4905, 1e-4);
  EXPECT_NEAR(last["pitch_rate"].get<double>(), -0.2, 1e-6);
  EXPECT_EQ(bridge.terminate(), 0);
}

INSTANTIATE_TEST_SUITE_P(Autopilots, FcBridgePeer, ::testing::Values("px4", "ardupilot"));

}  // namespace
}  // namespace cover::fc_bridge
