// Scenario 2 through the motion-capture path as real processes: cover-launch
// config/launch/scenario2_mocap.yaml (cover-sim --mocap vrpn, cover-mocap-relay, the agents)
// in lockstep, with the default noise and 1 % dropouts. DDS domains 132-139.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "cover/test/time_scale.hpp"
#include "process_support.hpp"

namespace {

using namespace std::chrono_literals;

std::uint16_t free_tcp_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
  socklen_t n = sizeof a;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &n);
  ::close(fd);
  return ntohs(a.sin_port);
}

using cover::test::scaled;

TEST(MocapScenario, Scenario2InLockstepThroughTheRelayLandsWithin5cm) {
  const auto claim = cover::dds::DomainClaim::claim_any(132, 139);
  const std::string run_dir = cover::test::scratch_path("run");
  cover::process::SpawnOptions spawn;
  spawn.log_file = cover::test::scratch_path("launch.log");
  cover::process::ChildProcess launch(
      {cover::test::bin("cover-launch"),
       std::string(COVER_CONFIG_DIR) + "/launch/scenario2_mocap.yaml", "--domain",
       std::to_string(claim.domain()), "--run-dir", run_dir, "--var",
       "mocap_port=" + std::to_string(free_tcp_port())},
      spawn);
  const auto code = launch.wait(scaled(120s));
  ASSERT_TRUE(code.has_value()) << "cover-launch still running after 120 s";
  ASSERT_EQ(*code, 0) << "see " << run_dir;
  std::ifstream in(run_dir + "/result.json");
  const auto result = nlohmann::json::parse(in);
  EXPECT_TRUE(result["success"].get<bool>()) << result.dump(2);
  EXPECT_LE(result["landing_error_m"].get<double>(), 0.05) << result.dump(2);
  std::printf("scenario2 lockstep through the mocap relay: landing %.3f m, %s\n",
              result["landing_error_m"].get<double>(), result["status"].get<std::string>().c_str());
  // Every tick found its relative states: the agent never stepped on missing inputs.
  std::ifstream agent(run_dir + "/uav0.log");
  const std::string log((std::istreambuf_iterator<char>(agent)), std::istreambuf_iterator<char>());
  EXPECT_EQ(log.find("inputs missing"), std::string::npos);
}

TEST(MocapScenario, ABadMocapFlagIsAUsageError) {
  for (const std::string value : {"tcp", "vrpn:0", "vrpn:70000", "vrpn:12x"}) {
    cover::process::SpawnOptions spawn;
    spawn.log_file = cover::test::scratch_path("sim.log");
    cover::process::ChildProcess sim({cover::test::bin("cover-sim"), "--mocap", value}, spawn);
    const auto code = sim.wait(scaled(30s));
    ASSERT_TRUE(code.has_value());
    EXPECT_EQ(*code, 2) << value;
    std::ifstream log(spawn.log_file);
    const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("--mocap"), std::string::npos) << text;
  }
}

}  // namespace
