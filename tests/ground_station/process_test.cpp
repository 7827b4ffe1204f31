// cover-ground-station as a real process, its API through bare sockets: --help and the exit
// codes, the token on a network bind, the state rows' rate, a status sample's row pushed as
// it arrives, its settings file, malformed, oversized and token-less requests answered with
// a reason while the process goes on.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include "cover/clock/clock.hpp"
#include "cover/dds/domain_claim.hpp"
#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/process/child_process.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/test/time_scale.hpp"
#include "cover/test/wait_until.hpp"
#include "raw_ws.hpp"

namespace {

using cover::test::RawWs;
using cover::test::scaled;
using namespace std::chrono_literals;

// The station on a free port of this domain; its address read from its stdout.
class Station {
 public:
  explicit Station(int domain, std::vector<std::string> extra = {}) {
    const std::string web = cover::test::scratch_path("web");
    std::filesystem::create_directories(web);
    std::ofstream(web + "/index.html") << "<html>station</html>";
    std::vector<std::string> argv{
        COVER_GROUND_STATION,  "--port", "0", "--web-dir", web, "--dds", "fastdds", "--domain",
        std::to_string(domain)};
    argv.insert(argv.end(), extra.begin(), extra.end());
    cover::process::SpawnOptions options;
    options.capture_stdout = true;
    options.log_file = cover::test::scratch_path("station.log");
    child = std::make_unique<cover::process::ChildProcess>(argv, options);
    const auto line = child->read_line(scaled(20000ms));
    if (!line) return;
    std::smatch m;
    static const std::regex address(R"(open http://[^:]+:(\d+)/\?token=([0-9a-zA-Z_-]+))");
    if (std::regex_search(*line, m, address)) {
      port = static_cast<std::uint16_t>(std::stoi(m[1]));
      token = m[2];
    }
  }
  ~Station() {
    if (child) child->terminate(5000ms, 2);
  }
  std::unique_ptr<cover::process::ChildProcess> child;
  std::uint16_t port = 0;
  std::string token;
};

struct Outcome {
  int exit_code = -1;
  std::string output;
};

Outcome run(const std::vector<std::string>& argv) {
  cover::process::SpawnOptions options;
  options.capture_stdout = true;
  options.log_file = cover::test::scratch_path("run.log");
  cover::process::ChildProcess child(argv, options);
  Outcome r;
  while (auto line = child.read_line(scaled(20000ms))) r.output += *line + "\n";
  r.exit_code = child.wait(scaled(20000ms)).value_or(-1);
  std::ifstream log(options.log_file);
  r.output += std::string(std::istreambuf_iterator<char>(log), {});
  return r;
}

// The reply to one request (state rows skipped), as JSON; null when none came.
nlohmann::json reply_to(RawWs& ws, const std::string& request) {
  ws.send_text(request);
  const auto deadline = std::chrono::steady_clock::now() + scaled(15000ms);
  while (std::chrono::steady_clock::now() < deadline) {
    const std::string text = ws.read_text(scaled(15000ms));
    if (text.empty()) break;
    auto j = nlohmann::json::parse(text, nullptr, false);
    if (j.is_object() && j.value("type", "") == "reply") return j;
  }
  return nullptr;
}

}  // namespace

TEST(GroundStationProcess, HelpListsTheExitCodes) {
  const Outcome r = run({COVER_GROUND_STATION, "--help"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.output.find("--token-file"), std::string::npos);
  EXPECT_NE(r.output.find("Exit codes"), std::string::npos);
}

TEST(GroundStationProcess, NetworkBindWithoutATokenFileRefusesToStart) {
  const Outcome r = run({COVER_GROUND_STATION, "--bind", "0.0.0.0", "--port", "0"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--token-file"), std::string::npos) << r.output;
  const std::string short_token = cover::test::scratch_path("short.token");
  std::ofstream(short_token) << "abc\n";
  const Outcome bad =
      run({COVER_GROUND_STATION, "--bind", "0.0.0.0", "--port", "0", "--token-file", short_token});
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
}

TEST(GroundStationProcess, NetworkBindAsksTheTokenOfEveryRequest) {
  auto claim = cover::dds::DomainClaim::claim_any(170, 174);
  const std::string token_file = cover::test::scratch_path("station.token");
  std::ofstream(token_file) << "field-token-0123456789\n";
  Station station(claim.domain(), {"--bind", "0.0.0.0", "--token-file", token_file});
  ASSERT_NE(station.port, 0) << "no address printed";
  EXPECT_EQ(station.token, "field-token-0123456789");
  EXPECT_EQ(RawWs().get(station.port, "/", "", false), 401);
  EXPECT_EQ(RawWs().get(station.port, "/ws", "", true), 401);
  EXPECT_EQ(RawWs().get(station.port, "/?token=field-token-0123456789", "", false), 200);
  RawWs ws;
  EXPECT_EQ(ws.get(station.port, "/ws?token=field-token-0123456789", "", true), 101);
}

TEST(GroundStationProcess, StateRowsComeAtTheRateAndBadRequestsGetAReason) {
  auto claim = cover::dds::DomainClaim::claim_any(170, 174);
  Station station(claim.domain());
  ASSERT_NE(station.port, 0) << "no address printed";
  EXPECT_EQ(station.token.size(), 32u);
  RawWs ws;
  ASSERT_EQ(ws.get(station.port, "/ws", "", true), 101);
  // The state rows at >= 5 Hz (10 Hz by default): 10 within 2 s of the first.
  const std::string first = ws.read_text(scaled(5000ms));
  ASSERT_FALSE(first.empty());
  const auto start = std::chrono::steady_clock::now();
  int states = 0;
  while (states < 10 && std::chrono::steady_clock::now() - start < scaled(2000ms)) {
    const auto j = nlohmann::json::parse(ws.read_text(scaled(2000ms)), nullptr, false);
    if (j.is_object() && j.value("type", "") == "state") ++states;
  }
  EXPECT_EQ(states, 10);

  auto r = reply_to(ws, "{not json");
  ASSERT_TRUE(r.is_object());
  EXPECT_FALSE(r["ok"].get<bool>());
  r = reply_to(ws,
               R"({"op":"abort","id":"a1","task_id":"))" + std::string(100 * 1024, 'x') + "\"}");
  ASSERT_TRUE(r.is_object());
  EXPECT_NE(r["message"].get<std::string>().find("at most"), std::string::npos) << r;
  // Without the token a loopback page reads, but moves nothing.
  r = reply_to(ws, R"({"op":"fc","id":"f1","uav_id":0,"command":"arm"})");
  ASSERT_TRUE(r.is_object());
  EXPECT_EQ(r["id"], "f1");
  EXPECT_FALSE(r["ok"].get<bool>());
  EXPECT_NE(r["message"].get<std::string>().find("token"), std::string::npos) << r;
  // With it, a task the task file's checks refuse names its field.
  RawWs commander;
  ASSERT_EQ(commander.get(station.port, "/ws?token=" + station.token, "", true), 101);
  r = reply_to(
      commander,
      R"({"op":"submit","id":"s1","task":{"task_id":"t","uav_id":0,"processes":[{"from_ugv":0,"to_ugv":1,)"
      R"("initial_point_m":[0,0,1.1],"transition_point_m":[0,0,1.1],"final_point_m":[0,0,0.25],)"
      R"("final_action":"land","vmax_m_s":0,"amax_m_s2":2}]}})");
  ASSERT_TRUE(r.is_object());
  EXPECT_FALSE(r["ok"].get<bool>());
  EXPECT_EQ(r.value("field", ""), "vmax_m_s") << r;
  // The process went on through all of it.
  EXPECT_FALSE(station.child->wait(0ms).has_value());
  EXPECT_EQ(RawWs().get(station.port, "/", "", false), 200);
}

TEST(GroundStationProcess, PortInUseExitsFour) {
  auto claim = cover::dds::DomainClaim::claim_any(170, 174);
  Station first(claim.domain());
  ASSERT_NE(first.port, 0);
  const Outcome second = run({COVER_GROUND_STATION, "--port", std::to_string(first.port), "--dds",
                              "fastdds", "--domain", std::to_string(claim.domain())});
  EXPECT_EQ(second.exit_code, 4) << second.output;
}

// A status sample's row reaches the page as it arrives, not at the next state row (1 Hz
// here): a "rows" message with the server's receive time and the sample's wall-clock stamp.
TEST(GroundStationProcess, AStatusSampleIsPushedAsItArrives) {
  auto claim = cover::dds::DomainClaim::claim_any(170, 174);
  Station station(claim.domain(), {"--state-rate-hz", "1", "--uavs", "1", "--ugvs", "1"});
  ASSERT_NE(station.port, 0) << "no address printed";
  RawWs ws;
  ASSERT_EQ(ws.get(station.port, "/ws", "", true), 101);
  ASSERT_FALSE(ws.read_text(scaled(5000ms)).empty());  // the first state: the page is served
  cover::dds::ParticipantOptions options;
  options.domain_id = claim.domain();
  options.vendor = cover::dds::Vendor::FastDds;
  cover::dds::Participant participant(options);
  auto writer = participant.make_writer(cover::dds::topics::uav_status(0));
  ASSERT_TRUE(writer.wait_for_readers(1, scaled(10000ms)));
  int pushed = 0;
  double worst_ms = 0.0;
  for (int i = 0; i < 5; ++i) {
    cover::msg::UavStatus status;
    status.uav_id = 0;
    status.stamp_ns = cover::clock::system_ns();
    status.task_id = "push-" + std::to_string(i);
    ASSERT_TRUE(writer.write(status));
    const auto deadline = std::chrono::steady_clock::now() + scaled(2000ms);
    while (std::chrono::steady_clock::now() < deadline) {
      const auto j = nlohmann::json::parse(ws.read_text(scaled(2000ms)), nullptr, false);
      if (!j.is_object() || j.value("type", "") != "rows") continue;
      const auto& row = j["rows"][0];
      if (row["last"].value("task_id", "") != status.task_id) continue;
      EXPECT_EQ(row["kind"], "uav-agent");
      EXPECT_DOUBLE_EQ(row["source_ms"].get<double>(), static_cast<double>(status.stamp_ns) / 1e6);
      EXPECT_GE(row["recv_ms"].get<double>(), row["source_ms"].get<double>());
      worst_ms = std::max(worst_ms,
                          static_cast<double>(cover::clock::system_ns() - status.stamp_ns) / 1e6);
      ++pushed;
      break;
    }
  }
  EXPECT_EQ(pushed, 5);
  // Well inside the 1 s between two state rows (a loaded machine included).
  EXPECT_LT(worst_ms, 500.0 * cover::test::time_scale());
}

// config/ground_station.yaml's keys, a flag on top of them; a bad key exits 2 naming it.
TEST(GroundStationProcess, ConfigKeysApplyAndBadOnesExitTwo) {
  const std::string bad = cover::test::scratch_path("bad_station.yaml");
  std::ofstream(bad) << "ground_station: {state_rate_hz: 500}\n";
  const Outcome r = run({COVER_GROUND_STATION, "--config", bad, "--port", "0"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("ground_station.state_rate_hz"), std::string::npos) << r.output;
  const std::string network = cover::test::scratch_path("network_station.yaml");
  std::ofstream(network) << "ground_station: {bind: 0.0.0.0}\n";
  const Outcome n = run({COVER_GROUND_STATION, "--config", network, "--port", "0"});
  EXPECT_EQ(n.exit_code, 2) << n.output;
  EXPECT_NE(n.output.find("token"), std::string::npos) << n.output;
}
