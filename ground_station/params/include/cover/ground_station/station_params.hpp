#pragma once

#include <string>

#include "cover/config/param_fields.hpp"
#include "cover/vocabulary/fleet_size.hpp"

namespace cover::ground_station {

// cover-ground-station's settings (config/ground_station.yaml, section `ground_station`;
// every key optional). Its command-line flags, where given, override them. The rows' stale
// thresholds are `cover fleet`'s (tools/cover fleet_view.cpp), not set here: the page and the
// terminal must agree on when a vehicle is lost.
struct StationParams {
  std::string bind = "127.0.0.1";
  int port = 8080;         // 0: any free port (printed)
  std::string token_file;  // "": a new token, printed once with the address
  std::string record_dir = ".";
  int uavs = fleet::kDefaultUavs;
  int ugvs = fleet::kDefaultUgvs;
  // The whole state (tasks, live plots, 3D view, every row's age) at this rate; a status
  // sample that changes what its row shows is pushed as it arrives, within push_coalesce_ms.
  double state_rate_hz = 10.0;
  double push_coalesce_ms = 5.0;
  int max_clients = 16;
  int client_queue_kib = 1024;
  double slow_client_timeout_s = 2.0;
  double manager_query_period_s = 0.5;
  double command_timeout_s = 5.0;

  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("bind", self.bind,
          Field("",
                "address to listen on; any but loopback needs token_file (every request "
                "must then carry the token)"));
    visit("port", self.port,
          Field("", "TCP port of the page; 0: any free port, printed")
              .at_least(0.0)
              .at_most(65535.0));
    visit("token_file", self.token_file,
          Field("",
                "file whose first line (>= 16 characters) is the token; empty: a new token "
                "printed once with the page's address"));
    visit("record_dir", self.record_dir,
          Field("", "folder of the recordings started from the page"));
    visit("uavs", self.uavs, Field("", "UAV ids 0..N-1 listened for").at_least(1.0).at_most(64.0));
    visit("ugvs", self.ugvs, Field("", "UGV ids 0..N-1 listened for").at_least(1.0).at_most(64.0));
    visit("state_rate_hz", self.state_rate_hz,
          Field("Hz", "rate of the whole state (tasks, live plots, 3D view, rows' ages)")
              .at_least(1.0)
              .at_most(50.0));
    visit("push_coalesce_ms", self.push_coalesce_ms,
          Field("ms",
                "a status sample that changes its row's text is pushed at once, or at most "
                "this long after it "
                "arrives when a message went out less than this ago; the rows heard meanwhile "
                "go in the same message (at most one message per window)")
              .at_least(0.0)
              .at_most(100.0));
    visit("max_clients", self.max_clients,
          Field("", "pages served at once").at_least(1.0).at_most(256.0));
    visit("client_queue_kib", self.client_queue_kib,
          Field("KiB", "bytes waiting for one page before its new messages are dropped")
              .at_least(16.0)
              .at_most(65536.0));
    visit("slow_client_timeout_s", self.slow_client_timeout_s,
          Field("s", "a page whose queue stays full this long (not reading) is disconnected")
              .at_least(0.1)
              .at_most(60.0));
    visit("manager_query_period_s", self.manager_query_period_s,
          Field("s", "how often the task manager's task list is asked for")
              .at_least(0.05)
              .at_most(10.0));
    visit("command_timeout_s", self.command_timeout_s,
          Field("s", "how long a task manager's or an autopilot's answer to the page is awaited")
              .at_least(0.1)
              .at_most(60.0));
  }

  static StationParams load_file(const std::string& path);
  static StationParams from_yaml(const YAML::Node& document, const std::string& source);
  void validate() const;
};

}  // namespace cover::ground_station
