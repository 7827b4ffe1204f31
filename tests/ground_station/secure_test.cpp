// cover-ground-station under DDS-Security, as real processes of one secure Fast DDS fleet
// (`cover security init`): the simulator with a simulated PX4, both UGV agents, the UAV
// agent, the flight-controller bridge and the task manager, each with its own identity.
//  - The station as ground-station-0 reads the fleet, submits a task, and arms the UAV.
//  - A station whose identity may read everything a ground station reads but publish
//    nothing that moves a vehicle (ground-station-1's permissions narrowed and re-signed by
//    the fleet's own CA: a viewer's station) reads the fleet too; its arm and its task are
//    refused: the autopilot stays disarmed until ground-station-0 arms it, the task manager
//    lists only ground-station-0's task.
// The stations' API through a bare WebSocket (raw_ws.hpp).
#include <gtest/gtest.h>

#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cover/test/time_scale.hpp"
#include "cover/test/wait_until.hpp"
#include "process_support.hpp"
#include "raw_ws.hpp"

namespace {

namespace fs = std::filesystem;
using cover::process::ChildProcess;
using cover::test::scaled;
using namespace std::chrono_literals;
using Json = nlohmann::json;

constexpr int kDomain = 187;
constexpr const char* kVendor = "fastdds";

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// `cover security init` of a 2-UGV, 1-UAV, 2-station fleet; empty on failure (logged). Every
// process is told the fleet's size (as cover-launch does): a reader on a UAV the fleet does
// not have is refused by the permissions.
fs::path make_fleet() {
  const fs::path dir = cover::test::scratch_dir() / "fleet";
  ChildProcess init({COVER_CLI, "security", "init", dir.string(), "--vendor", kVendor, "--ugvs",
                     "2", "--uavs", "1", "--ground-stations", "2", "--days", "2"},
                    cover::test::quiet(kVendor, kDomain, "init.log"));
  return init.wait(scaled(60000ms)).value_or(-1) == 0 ? dir : fs::path();
}

// ground-station-1 without what moves a vehicle among what it may publish
// (cover/fc/request: arm, offboard, land, disarm; cover/manager/request: submit, abort;
// cover/task/abort), signed again by the fleet's CA: a valid identity of the fleet, a
// viewer's station.
void narrow_to_viewer(const fs::path& fleet) {
  const fs::path identity = fleet / "identities" / "ground-station-1";
  std::string xml = read_text(identity / "permissions.xml");
  const auto publish = xml.find("<publish>");
  ASSERT_NE(publish, std::string::npos) << xml;
  for (const std::string topic :
       {"cover/fc/request", "cover/manager/request", "cover/task/abort"}) {
    const std::string grant = "<topic>" + topic + "</topic>";
    const auto at = xml.find(grant, publish);
    ASSERT_NE(at, std::string::npos) << topic << " not granted: " << xml;
    ASSERT_LT(at, xml.find("</publish>", publish)) << topic << " is not published by it";
    xml.erase(at, grant.size());
    ASSERT_EQ(xml.find(grant, publish), std::string::npos) << topic << " granted twice";
  }
  // Nothing left to publish: no <publish> rule at all (an empty <topics> is not valid XML
  // of the permissions schema).
  const auto end = xml.find("</publish>", publish) + std::string("</publish>").size();
  if (xml.substr(publish, end - publish).find("<topic>") == std::string::npos) {
    xml.erase(publish, end - publish);
  }
  std::ofstream(identity / "permissions.xml") << xml;
  const std::string command =
      "openssl smime -sign -in '" + (identity / "permissions.xml").string() + "' -text -out '" +
      (identity / "permissions.p7s").string() + "' -signer '" +
      (fleet / "permissions_ca.pem").string() + "' -inkey '" + (fleet / "ca.key").string() + "'";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
}

std::vector<std::string> operator+(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// A station's page over a bare WebSocket: its state rows and its replies.
class StationClient {
 public:
  StationClient(const fs::path& fleet, const std::string& identity, const std::string& log)
      : child_(start(fleet, identity, log)) {
    const auto line = child_->read_line(scaled(60000ms));
    std::smatch m;
    static const std::regex address(R"(open http://[^:]+:(\d+)/\?token=([0-9a-zA-Z_-]+))");
    if (line && std::regex_search(*line, m, address)) {
      connected_ = ws_.get(static_cast<std::uint16_t>(std::stoi(m[1])), "/ws?token=" + m[2].str(),
                           "", true) == 101;
    }
  }
  bool connected() const { return connected_; }
  ChildProcess& process() { return *child_; }

  // The newest state row; null when none came within `timeout`.
  Json state(std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
      const auto j = Json::parse(ws_.read_text(timeout), nullptr, false);
      if (j.is_object() && j.value("type", "") == "state") return j;
    }
    return nullptr;
  }
  // The reply to `request` (state rows skipped); null when none came.
  Json call(const Json& request) {
    ws_.send_text(request.dump());
    const auto deadline = std::chrono::steady_clock::now() + scaled(60000ms);
    while (std::chrono::steady_clock::now() < deadline) {
      const auto j = Json::parse(ws_.read_text(scaled(60000ms)), nullptr, false);
      if (j.is_object() && j.value("type", "") == "reply" && j["id"] == request["id"]) return j;
    }
    return nullptr;
  }
  // Whether a state row within `timeout` (scaled by wait_until) satisfies `condition`.
  template <typename Condition>
  bool wait_for(Condition condition, std::chrono::milliseconds timeout) {
    return cover::test::wait_until(
        [&] {
          const Json s = state(scaled(2000ms));
          return s.is_object() && condition(s);
        },
        timeout, 0ms);
  }

 private:
  static std::unique_ptr<ChildProcess> start(const fs::path& fleet, const std::string& identity,
                                             const std::string& log) {
    auto options = cover::test::quiet(kVendor, kDomain, log);
    options.capture_stdout = true;
    return std::make_unique<ChildProcess>(
        std::vector<std::string>{cover::test::bin("cover-ground-station"), "--port", "0",
                                 "--record-dir", cover::test::scratch_dir().string(), "--uavs", "1",
                                 "--ugvs", "2", "--security", fleet.string(), "--identity",
                                 identity},
        options);
  }
  std::unique_ptr<ChildProcess> child_;
  cover::test::RawWs ws_;
  bool connected_ = false;
};

// The rows of `kinds` a page lists, not stale.
int fresh_rows(const Json& state, const std::set<std::string>& kinds) {
  int fresh = 0;
  for (const auto& row : state["fleet"]) {
    if (!row.value("stale", true) && kinds.count(row.value("kind", "")) > 0) ++fresh;
  }
  return fresh;
}
const std::set<std::string> kVehicleKinds = {"sim", "ugv-agent", "uav-agent", "fc-bridge"};
bool lists_the_vehicles(const Json& state) {
  return fresh_rows(state, kVehicleKinds) == 5;  // two UGV agents
}
// The task manager's row with its answer to the station's query: a station that may ask it.
// (A station that may not ask can still have a row for it, from the manager's clock requests,
// which every station may read: a row without an answer.)
bool lists_the_manager_answering(const Json& state) {
  for (const auto& row : state["fleet"]) {
    if (row.value("kind", "") == "task-manager" && !row.value("stale", true) &&
        row["last"].is_object())
      return true;
  }
  return false;
}
bool lists_the_fleet(const Json& state) {
  return lists_the_vehicles(state) && lists_the_manager_answering(state);
}

// Fast DDS 2.9 can leave a secure pair of participants without data for good on a loaded
// machine (docs/security.md, known weaknesses: seen here under load average 34, a station
// hearing the UAV agent and bridge but never the simulator or the UGV agents); what recovers
// it is a new participant. A station that does not list what `lists` asks within 45 s
// (scaled) is started once more, and then must within 90 s.
template <typename Condition>
std::unique_ptr<StationClient> listing_station(const fs::path& fleet, const std::string& identity,
                                               Condition lists) {
  for (int attempt = 0; attempt < 2; ++attempt) {
    const std::string log = identity + "_" + std::to_string(attempt) + ".log";
    auto station = std::make_unique<StationClient>(fleet, identity, log);
    if (station->connected() && station->wait_for(lists, attempt == 0 ? 45000ms : 90000ms)) {
      return station;
    }
    std::cout << identity << ": not listing the fleet (" << cover::test::scratch_path(log)
              << "): " << (attempt == 0 ? "a new participant" : "giving up") << std::endl;
    if (station->connected()) std::cout << station->state(scaled(2000ms)).dump() << std::endl;
  }
  return nullptr;
}

// UAV 0's autopilot armed, as its bridge's row reports it; nullopt without the row.
std::optional<bool> armed(const Json& state) {
  for (const auto& row : state["fleet"]) {
    if (row.value("kind", "") == "fc-bridge" && row["last"].is_object() &&
        row["last"].contains("armed"))
      return row["last"]["armed"].get<bool>();
  }
  return std::nullopt;
}

}  // namespace

TEST(GroundStationSecure, StationCommandsAsItsIdentityAndAViewerCannotArm) {
  const auto claim = cover::test::claim_domain(kDomain);
  const fs::path fleet = make_fleet();
  ASSERT_FALSE(fleet.empty()) << "cover security init failed: "
                              << cover::test::scratch_path("init.log");
  narrow_to_viewer(fleet);
  if (HasFatalFailure()) return;
  const auto secure = [&](const std::string& identity) {
    return std::vector<std::string>{"--security", fleet.string(), "--identity", identity};
  };
  const auto spawn = [&](const std::vector<std::string>& argv, const std::string& name) {
    return std::make_unique<ChildProcess>(argv,
                                          cover::test::quiet(kVendor, kDomain, name + ".log"));
  };
  const std::string fc_port = std::to_string(16540 + 2 * (kDomain - 170));
  const std::string autopilot_port = std::to_string(16580 + 2 * (kDomain - 170));
  const std::string run_id = "gss_" + std::to_string(::getpid());
  using cover::test::bin;
  std::vector<std::unique_ptr<ChildProcess>> fleet_processes;
  fleet_processes.push_back(
      spawn(std::vector<std::string>{bin("cover-sim"), "--clock", "realtime", "--scenario",
                                     "scenario1", "--standing", "--run-id", run_id, "--fc", "px4",
                                     "--fc-peer-port-base", fc_port, "--fc-bind-port-base",
                                     autopilot_port} +
                secure("sim"),
            "sim"));
  for (int k = 0; k < 2; ++k) {
    fleet_processes.push_back(
        spawn(std::vector<std::string>{bin("cover-ugv-agent"), "--id", std::to_string(k),
                                       "--run-id", run_id} +
                  secure("ugv-agent-" + std::to_string(k)),
              "ugv" + std::to_string(k)));
  }
  fleet_processes.push_back(
      spawn(std::vector<std::string>{bin("cover-fc-bridge"), "--id", "0", "--autopilot", "px4",
                                     "--url", "udpin://127.0.0.1:" + fc_port} +
                secure("fc-bridge-0"),
            "bridge"));
  fleet_processes.push_back(spawn(std::vector<std::string>{bin("cover-uav-agent"), "--id", "0",
                                                           "--ugv-count", "2", "--fc-bridge"} +
                                      secure("uav-agent-0"),
                                  "uav"));
  const auto start_manager = [&](const std::string& log) {
    return spawn(std::vector<std::string>{bin("cover-task-manager"), "--uavs", "1", "--ugvs", "2",
                                          "--db", cover::test::scratch_path("tasks.db")} +
                     secure("task-manager"),
                 log);
  };
  fleet_processes.push_back(start_manager("manager"));

  // Both read the fleet through the handshake and their read permissions; the viewer's page
  // says why it has no task list, and has no answer of the task manager.
  auto operator_ptr = listing_station(fleet, "ground-station-0", lists_the_fleet);
  ASSERT_NE(operator_ptr, nullptr) << "the operator's station does not list the fleet";
  const auto viewer_ptr = listing_station(fleet, "ground-station-1", lists_the_vehicles);
  ASSERT_NE(viewer_ptr, nullptr) << "the viewer's station does not list the vehicles";
  StationClient& viewer_station = *viewer_ptr;
  EXPECT_TRUE(viewer_station.wait_for(
      [](const Json& s) {
        return s.value("manager", "").find("cover/manager/request") != std::string::npos &&
               !lists_the_manager_answering(s);
      },
      10000ms))
      << viewer_station.state(scaled(2000ms)).dump(1);
  ASSERT_TRUE(operator_ptr->wait_for([](const Json& s) { return armed(s) == false; }, 30000ms))
      << "no disarmed autopilot to start from";

  const Json task = {{"task_id", "secure-1"},
                     {"uav_id", 0},
                     {"processes",
                      {{{"from_ugv", 0},
                        {"to_ugv", 1},
                        {"initial_point_m", {0, 0, 1.1}},
                        {"transition_point_m", {0, 0, 1.1}},
                        {"final_point_m", {0, 0, 0.05}},
                        {"final_action", "land"},
                        {"vmax_m_s", 1.0},
                        {"amax_m_s2", 2.0}}}}};
  Json viewer_task = task;
  viewer_task["task_id"] = "viewer-1";
  // The viewer's arm and submit: its participant may not write cover/fc/request nor
  // cover/manager/request, so each request is refused before it leaves; the autopilot stays
  // disarmed, the task manager never hears of the task.
  const Json refused =
      viewer_station.call({{"op", "fc"}, {"id", "v1"}, {"uav_id", 0}, {"command", "arm"}});
  ASSERT_TRUE(refused.is_object()) << "no reply to the viewer's arm";
  EXPECT_FALSE(refused["ok"].get<bool>()) << refused;
  std::cout << "viewer's arm: " << refused["message"].get<std::string>() << std::endl;
  const Json viewer_submit =
      viewer_station.call({{"op", "submit"}, {"id", "v2"}, {"task", viewer_task}});
  ASSERT_TRUE(viewer_submit.is_object()) << "no reply to the viewer's submit";
  EXPECT_FALSE(viewer_submit["ok"].get<bool>()) << viewer_submit;
  std::cout << "viewer's submit: " << viewer_submit["message"].get<std::string>() << std::endl;
  // Armed would show within a state row or two (10 Hz) of an accepted arm: 3 s of rows
  // (scaled) with the autopilot disarmed in each.
  EXPECT_FALSE(operator_ptr->wait_for([](const Json& s) { return armed(s) == true; }, 3000ms))
      << "the viewer's arm reached the autopilot";

  // The operator's station, as ground-station-0: a task submitted, then the arm accepted.
  // On a loaded machine the secure fleet can answer what the test cannot take as the
  // requirement's answer; each is asked again until a deadline:
  //  - "UAV 0 is not up" / "UGV k is not publishing": the manager does not hear an agent (a
  //    starved agent, or the Fast DDS 2.9 secure pair stall: then only a new participant
  //    recovers it, docs/security.md: the manager is restarted once, after 15 s of it);
  //  - "no task manager reachable": the station's request writer never met the manager (the
  //    stall again: a new station);
  //  - "did not answer": the reply was late; the same task asked again is answered "queued"
  //    whether or not the first one was taken (a submission is idempotent).
  const auto manager_lost_the_fleet = [](const std::string& why) {
    return why.find("is not publishing") != std::string::npos ||
           why.find("is not up") != std::string::npos;
  };
  const auto accepted = [](const Json& reply) { return reply.value("ok", false); };
  Json submitted;
  int attempt = 0;
  bool manager_restarted = false;
  const auto since = std::chrono::steady_clock::now();
  cover::test::wait_until(
      [&] {
        submitted = operator_ptr->call(
            {{"op", "submit"}, {"id", "s" + std::to_string(++attempt)}, {"task", task}});
        const std::string why = submitted.value("message", "");
        if (!submitted.is_object() || accepted(submitted)) return true;
        std::cout << "submit " << attempt << ": " << why << std::endl;
        if (manager_lost_the_fleet(why) && !manager_restarted &&
            std::chrono::steady_clock::now() - since > scaled(15000ms)) {
          std::cout << "a new task manager participant" << std::endl;
          manager_restarted = true;
          fleet_processes.back()->terminate(scaled(5000ms), SIGINT);
          fleet_processes.back() = start_manager("manager_1");
          return !operator_ptr->wait_for(lists_the_fleet, 90000ms);
        }
        if (why.find("no task manager reachable") != std::string::npos) {
          std::cout << "a new station participant" << std::endl;
          operator_ptr.reset();
          operator_ptr = listing_station(fleet, "ground-station-0", lists_the_fleet);
          return operator_ptr == nullptr;
        }
        return !manager_lost_the_fleet(why) && why.find("did not answer") == std::string::npos;
      },
      90000ms, 1000ms);
  ASSERT_NE(operator_ptr, nullptr) << "the operator's station does not list the fleet";
  ASSERT_TRUE(submitted.is_object()) << "no reply to the submit";
  EXPECT_TRUE(accepted(submitted)) << submitted;
  EXPECT_TRUE(operator_ptr->wait_for(
      [](const Json& s) {
        bool listed = false;
        for (const auto& t : s["tasks"]) {
          if (t.value("task_id", "") == "viewer-1") return false;
          listed = listed || t.value("task_id", "") == "secure-1";
        }
        return listed;
      },
      30000ms))
      << "the task manager does not list the submitted task (or lists the viewer's)";
  const Json arm =
      operator_ptr->call({{"op", "fc"}, {"id", "a1"}, {"uav_id", 0}, {"command", "arm"}});
  ASSERT_TRUE(arm.is_object()) << "no reply to the operator's arm";
  EXPECT_TRUE(arm["ok"].get<bool>()) << arm;
  EXPECT_TRUE(operator_ptr->wait_for([](const Json& s) { return armed(s) == true; }, 30000ms))
      << "the operator's accepted arm did not arm the autopilot";

  for (auto* station : {operator_ptr.get(), viewer_ptr.get()}) {
    station->process().terminate(scaled(5000ms), SIGINT);
    EXPECT_EQ(station->process().exit_code().value_or(-1), 0);
  }
  for (auto it = fleet_processes.rbegin(); it != fleet_processes.rend(); ++it) {
    (*it)->terminate(scaled(5000ms), SIGINT);
  }
}
