#pragma once

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "cover/msg/types.hpp"

namespace cover::cli {

// What `cover fleet` lists, in this order: one row per vehicle or process heard on the
// domain. No DDS here: the command hands in what its readers receive.
enum class FleetKind { UavAgent, FcBridge, UgvAgent, TaskManager, Sim, MocapRelay, Process };

// "uav-agent", "fc-bridge", "ugv-agent", "task-manager", "sim", "mocap-relay", "process".
const char* kind_name(FleetKind kind);

struct FleetRow {
  FleetKind kind = FleetKind::Process;
  std::optional<std::uint32_t> id;     // the UAV or UGV id; none for the other kinds
  std::vector<std::string> processes;  // "host/process" as named in the clock exchange;
                                       // two or more: one id claimed by several processes
  double age_s = 0.0;                  // since its last message
  double stale_after_s = 0.0;          // three of its slowest message's periods
  bool stale = false;                  // age_s > stale_after_s
  std::uint64_t messages = 0;
  std::string state;
  std::string failsafe = "-";     // "-": not a notion of this kind
  std::string task = "-";         // "-": none
  std::string autopilot = "-";    // UAV agent and bridge: the autopilot as its bridge reports it
  nlohmann::ordered_json detail;  // the last status sample, as on the wire (JSON)
};

// The fleet as heard so far. Times are monotonic nanoseconds of arrival.
class FleetView {
 public:
  // `manager_query_period_s`: how often the command asks the task manager (its row must not
  // turn stale between two queries).
  explicit FleetView(double manager_query_period_s = 1.0);

  // Each status sample with its JSON (the row's detail).
  void heard(const msg::UavStatus& s, nlohmann::ordered_json json, std::int64_t at_ns);
  void heard(const msg::FcState& s, nlohmann::ordered_json json, std::int64_t at_ns);
  void heard(const msg::UgvStatus& s, nlohmann::ordered_json json, std::int64_t at_ns);
  void heard(const msg::SimClock& s, nlohmann::ordered_json json, std::int64_t at_ns);
  // The task manager's answer to a query of every task not ended.
  void heard(const msg::ManagerReply& reply, nlohmann::ordered_json json, std::int64_t at_ns);
  // A process named in the clock exchange ("host/cover-uav-agent-0"), asking or answering:
  // the only periodic message of the task manager, the simulator's name, the hosts.
  void heard_peer(const std::string& name, std::int64_t at_ns);
  // A writer of the kind's status (the task manager: of its replies) matched one of the
  // command's readers: a process is there, its first message not heard yet. A row from
  // then on (nothing but a row to wait for: the first call counts).
  void discovered(FleetKind kind, std::optional<std::uint32_t> id, std::int64_t at_ns);

  bool empty() const { return entries_.empty(); }
  // True when every row heard so far has been described: its status heard (the task
  // manager: its answer to the query), and named in the clock exchange or first heard at
  // least `naming_grace_ns` ago (the names come once a second, and nobody names a
  // simulator no UAV agent asks). A listing that ends before prints "still listening" for
  // the rows without a status rather than a state it has not had time to hear.
  bool settled(std::int64_t now_ns, std::int64_t naming_grace_ns) const;
  std::vector<FleetRow> rows(std::int64_t now_ns) const;

 private:
  // Kind, id (-1: none), and for kinds without an id the process name ("": one that
  // published its status without naming itself, e.g. the simulator's clock).
  using Key = std::tuple<FleetKind, std::int64_t, std::string>;
  struct Entry {
    std::int64_t status_ns = -1;  // its own status topic, -1: none heard
    std::int64_t peer_ns = -1;    // the clock exchange, -1: none heard
    std::int64_t first_ns = -1;   // its first message of either, or its discovery
    std::uint64_t messages = 0;
    std::set<std::string> processes;
    std::string state;
    std::string failsafe = "-";
    std::string task = "-";
    std::string autopilot = "-";
    nlohmann::ordered_json detail;
  };

  Entry& status_entry(FleetKind kind, std::int64_t id, std::int64_t at_ns);
  std::map<Key, Entry> merged() const;
  static bool described(FleetKind kind, const Entry& entry);
  FleetRow row(const Key& key, const Entry& entry, std::int64_t now_ns) const;

  double manager_query_period_s_;
  std::map<Key, Entry> entries_;
};

// A plain-text table, one row per line, with a header.
std::string fleet_table(const std::vector<FleetRow>& rows);
// One JSON object per row.
nlohmann::ordered_json fleet_json(const std::vector<FleetRow>& rows);

}  // namespace cover::cli
