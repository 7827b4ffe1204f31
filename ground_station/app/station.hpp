#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/ground_station/api.hpp"
#include "cover/ground_station/web_server.hpp"
#include "cover/process/child_process.hpp"
#include "cover/recording/fleet_topics.hpp"
#include "fc_client.hpp"
#include "fleet_listener.hpp"
#include "manager_client.hpp"
#include "sim_world.hpp"

namespace cover::ground_station {

struct StationOptions {
  WebServerOptions web;
  recording::FleetSize fleet;
  double state_rate_hz = 10.0;    // the page's fleet, task and live-plot rows
  double push_coalesce_ms = 5.0;  // a status sample's row is pushed within this
  double manager_query_period_s = 0.5;
  double command_timeout_s = 5.0;        // a task manager's or an autopilot's answer
  std::vector<std::string> record_argv;  // `cover record` and its DDS flags (-o is added)
  std::string record_dir = ".";
  int dds_domain = 0;  // with sim_run_id: the simulator's world segment
  std::string sim_run_id = "default";
};

// The adapter between the page's API and the fleet: the fleet as `cover fleet` hears it,
// the task manager's tasks, each UAV's live plot values and 3D poses, into one state
// message broadcast at state_rate_hz; each status sample's row pushed as it arrives (rows
// heard within push_coalesce_ms in one message); the page's requests into the task manager's and
// the bridges' requests on a worker thread, each answered with what they answered.
class Station {
 public:
  Station(dds::Participant& participant, StationOptions options);
  ~Station();
  Station(const Station&) = delete;
  Station& operator=(const Station&) = delete;

  std::uint16_t port() const { return server_->port(); }
  WebServerStats web_stats() const { return server_->stats(); }
  // Serves until SIGINT/SIGTERM.
  void run();

 private:
  struct Job {
    std::uint64_t client = 0;
    ApiRequest request;
  };
  // The latest live values of one UAV, for the plots and the 3D view.
  struct Live {
    std::optional<msg::UavCommand> command;
    std::optional<msg::ControlTrace> trace;
    std::optional<msg::ReferenceTrajectory> reference;
    std::map<std::uint32_t, msg::RelativeState> relative;  // by UGV
  };

  // A status row heard: when (CLOCK_REALTIME) and the sample's own stamp.
  struct Heard {
    std::int64_t source_ns = 0;
    std::int64_t received_ns = 0;
  };
  using RowKey = std::pair<cli::FleetKind, std::optional<std::uint32_t>>;

  void on_status(cli::FleetKind kind, std::optional<std::uint32_t> id, std::int64_t stamp_ns);
  void push_rows();
  nlohmann::json rows_json(const std::map<RowKey, Heard>& heard);
  void on_message(std::uint64_t client, bool has_token, const std::string& text);
  void work();
  void make_clients();
  void query_manager();
  std::string answer(const ApiRequest& request, bool& ok, std::string& field);
  std::string record(bool start, bool& ok);
  nlohmann::json state_json();
  nlohmann::json live_json();

  dds::Participant& participant_;
  StationOptions options_;
  std::atomic<bool> stopping_{false};

  // Before the listener: its readers call on_status() from their first sample on.
  std::mutex push_mutex_;
  std::condition_variable push_cv_;
  std::map<RowKey, Heard> heard_;
  // What each row showed when last pushed, and when it was heard (the push thread's own):
  // a sample that changes neither is no news, its age goes out with the next state.
  std::map<RowKey, std::string> pushed_shown_;
  std::map<RowKey, std::int64_t> pushed_heard_ns_;
  cli::FleetListener listener_;
  SimWorld world_;  // read by run()'s thread only

  std::mutex live_mutex_;
  std::map<std::uint32_t, Live> live_;
  std::vector<dds::Reader<msg::UavCommand>> command_readers_;
  std::vector<dds::Reader<msg::ControlTrace>> trace_readers_;
  std::vector<dds::Reader<msg::ReferenceTrajectory>> reference_readers_;
  std::vector<dds::Reader<msg::RelativeState>> relative_readers_;

  std::mutex tasks_mutex_;
  nlohmann::json tasks_ = nlohmann::json::array();
  std::string manager_note_ = "asking the task manager";

  std::mutex record_mutex_;
  std::unique_ptr<process::ChildProcess> recorder_;
  std::string record_file_;

  // The worker's lines to the task manager and the bridges, made once when it starts: a new
  // writer and reader per request would wait for discovery (and under DDS-Security for the
  // key exchange) on every request. Null with the reason when this identity may not publish
  // the request topic.
  std::unique_ptr<cli::ManagerClient> manager_client_;
  std::unique_ptr<cli::FcClient> fc_client_;
  std::string manager_client_error_;
  std::string fc_client_error_;

  std::mutex jobs_mutex_;
  std::condition_variable jobs_cv_;
  std::deque<Job> jobs_;

  std::unique_ptr<WebServer> server_;  // after the state its handlers use
  std::thread worker_;
  std::thread manager_thread_;
  std::thread push_thread_;
};

}  // namespace cover::ground_station
