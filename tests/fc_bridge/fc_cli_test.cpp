// `cover fc status|offboard|arm|land U` as an operator runs them, against cover-fc-bridge and
// the node-mavlink fake autopilot (tests/mavlink/peer/fake_autopilot.js): each waits for the
// autopilot's answer and exits 0 accepted, 1 refused (the reason printed), 3 no answer.
// No UAV agent runs: nothing streams setpoints, so the autopilot refuses OFFBOARD.

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "cover/dds/domain_claim.hpp"
#include "process_support.hpp"

namespace cover::fc_bridge {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

const fs::path kPeerDir = COVER_MAVLINK_PEER_DIR;

struct CliRun {
  int exit_code = -1;
  std::string output;  // stdout, every line
};

// `cover fc ...` on `domain`; its stdout captured, its stderr in the scratch log.
CliRun cover_fc(int domain, const std::vector<std::string>& args) {
  std::vector<std::string> argv{COVER_CLI, "fc"};
  argv.insert(argv.end(), args.begin(), args.end());
  argv.insert(argv.end(), {"--dds", "cyclone", "--domain", std::to_string(domain)});
  process::SpawnOptions options;
  options.capture_stdout = true;
  options.log_file = cover::test::scratch_path("cover_fc.log");
  process::ChildProcess cli(argv, options);
  CliRun run;
  while (const auto line = cli.read_line(test::scaled(20s))) run.output += *line + "\n";
  run.exit_code = cli.wait(test::scaled(20s)).value_or(-1);
  return run;
}

TEST(CoverFc, StatusAndOperatorCommandsWaitForTheAutopilotsAnswer) {
  const std::string node = test::find_node();
  if (node.empty()) GTEST_SKIP() << "node is not installed: the fake autopilot needs it";
  ASSERT_TRUE(fs::exists(kPeerDir / "node_modules" / "node-mavlink" / "package.json"))
      << "run scripts/setup (npm ci --prefix tests/mavlink/peer)";
  const auto claim = dds::DomainClaim::claim_any(200, 209);
  const int port = test::free_udp_port();
  process::SpawnOptions fake_options;
  fake_options.log_file = cover::test::scratch_path("fake_autopilot.log");
  process::ChildProcess fake({node, (kPeerDir / "fake_autopilot.js").string(), "--port",
                              std::to_string(port), "--autopilot", "px4", "--sysid", "9",
                              "--duration-s", std::to_string(60 * cover::test::whole_time_scale())},
                             fake_options);
  auto bridge = test::start_bridge(
      claim.domain(), {"--autopilot", "px4", "--url", "udpout://127.0.0.1:" + std::to_string(port),
                       "--clock", "system"});

  // Status: the link, the learned system id, disarmed.
  nlohmann::json status;
  ASSERT_TRUE(test::wait_until(
      [&] {
        const CliRun run = cover_fc(claim.domain(), {"status", "0", "--json", "--timeout", "2"});
        if (run.exit_code != 0) return false;
        status = nlohmann::json::parse(run.output);
        return status.value("link_ok", false);
      },
      30s))
      << status.dump();
  EXPECT_EQ(status["system_id"], 9);
  EXPECT_EQ(status["armed"], false);
  for (const char* key : {"link_ok", "autopilot", "armed", "mode", "hover_thrust"}) {
    EXPECT_TRUE(status.contains(key)) << key;
  }

  // OFFBOARD before any setpoint: refused, with the reason.
  const CliRun offboard = cover_fc(claim.domain(), {"offboard", "0"});
  EXPECT_EQ(offboard.exit_code, 1) << offboard.output;
  EXPECT_NE(offboard.output.find("REFUSED"), std::string::npos) << offboard.output;

  // The operator arms; the autopilot says yes, and status shows it.
  const CliRun arm = cover_fc(claim.domain(), {"arm", "0"});
  EXPECT_EQ(arm.exit_code, 0) << arm.output;
  EXPECT_TRUE(test::wait_until(
      [&] {
        const CliRun run = cover_fc(claim.domain(), {"status", "0", "--json", "--timeout", "2"});
        return run.exit_code == 0 && nlohmann::json::parse(run.output).value("armed", false);
      },
      10s));
  const CliRun land = cover_fc(claim.domain(), {"land", "0", "--json"});
  EXPECT_EQ(land.exit_code, 0) << land.output;
  EXPECT_EQ(nlohmann::json::parse(land.output)["result"], "FC_RESULT_ACCEPTED") << land.output;

  // No bridge for UAV 5: no answer, exit 3.
  const CliRun nobody = cover_fc(claim.domain(), {"arm", "5", "--timeout", "2"});
  EXPECT_EQ(nobody.exit_code, 3) << nobody.output;

  EXPECT_EQ(bridge.terminate(), 0);
  fake.terminate();
}

}  // namespace
}  // namespace cover::fc_bridge
