#include "fleet_view.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <string_view>
#include <utility>

namespace cover::cli {
namespace {

constexpr double kNsPerS = 1e9;

// The processes' names as they give them to the clock exchange (docs/time.md); a numbered
// one ends in its vehicle's id.
struct NamedKind {
  std::string_view prefix;
  FleetKind kind;
  bool numbered;
};
constexpr std::array<NamedKind, 6> kNamedKinds{{
    {"cover-uav-agent-", FleetKind::UavAgent, true},
    {"cover-fc-bridge-", FleetKind::FcBridge, true},
    {"cover-ugv-agent-", FleetKind::UgvAgent, true},
    {"cover-task-manager", FleetKind::TaskManager, false},
    {"cover-sim", FleetKind::Sim, false},
    {"cover-mocap-relay", FleetKind::MocapRelay, false},
}};

bool has_id(FleetKind kind) {
  return kind == FleetKind::UavAgent || kind == FleetKind::FcBridge || kind == FleetKind::UgvAgent;
}

// "FAILSAFE_EMERGENCY_HOVER" without "FAILSAFE_", in lower case: "emergency_hover".
std::string lower_after(const std::string& name, std::string_view prefix) {
  std::string text = name.rfind(prefix, 0) == 0 ? name.substr(prefix.size()) : name;
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

std::string seconds(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", s);
  return text;
}

// The autopilot in a few words: "px4 OFFBOARD armed", "ardupilot POSCTL disarmed link LOST".
std::string autopilot_summary(const msg::FcState& s) {
  if (s.autopilot == msg::FcAutopilot::FC_AUTOPILOT_UNKNOWN) {
    return std::string("no autopilot heard") + (s.link_ok ? "" : ", link LOST");
  }
  std::string text = lower_after(msg::to_string(s.autopilot), "FC_AUTOPILOT_");
  text +=
      " " + (s.mode_name.empty() ? lower_after(msg::to_string(s.mode), "FC_MODE_") : s.mode_name);
  text += s.armed ? " armed" : " disarmed";
  if (!s.link_ok) text += " link LOST";
  return text;
}

std::string uav_state(const msg::UavStatus& s) {
  std::string text;
  if (s.task_id.empty()) {
    text = "idle";
  } else {
    text = lower_after(msg::to_string(s.task_state), "TASK_") + " " +
           lower_after(msg::to_string(s.stage), "STAGE_") + " " +
           std::to_string(s.process_index + 1) + "/" + std::to_string(s.process_count);
  }
  return text + (s.armed ? ", armed" : ", disarmed");
}

std::string manager_state(const msg::ManagerReply& reply, std::string& task) {
  std::size_t queued = 0;
  std::size_t in_flight = 0;
  std::string flying;
  for (const msg::ManagedTask& t : reply.tasks) {
    if (t.state == msg::ManagedTaskState::MANAGED_QUEUED) {
      ++queued;
    } else if (t.state == msg::ManagedTaskState::MANAGED_DISPATCHED ||
               t.state == msg::ManagedTaskState::MANAGED_RUNNING) {
      ++in_flight;
      flying +=
          (flying.empty() ? "" : ", ") + t.task_id + " (UAV " + std::to_string(t.uav_id) + ")";
    }
  }
  task = flying.empty() ? "-" : flying;
  return std::to_string(queued) + " queued, " + std::to_string(in_flight) + " in flight";
}

// Past the kind's slowest periodic message by a margin: UAV status and bridge state 10 Hz
// (five periods: a killed agent's row turns red within 1 s on the operator's page, not
// after one), UGV status 1 Hz, the clock exchange 1 Hz (config/time_sync.yaml): three.
double stale_after_s(FleetKind kind, bool status_heard, double manager_query_period_s) {
  switch (kind) {
    case FleetKind::UavAgent:
    case FleetKind::FcBridge:
    case FleetKind::Sim:
      return status_heard ? 0.5 : 3.0;
    case FleetKind::TaskManager:
      return std::max(3.0, 2.0 * manager_query_period_s);
    default:
      return 3.0;
  }
}

}  // namespace

const char* kind_name(FleetKind kind) {
  switch (kind) {
    case FleetKind::UavAgent:
      return "uav-agent";
    case FleetKind::FcBridge:
      return "fc-bridge";
    case FleetKind::UgvAgent:
      return "ugv-agent";
    case FleetKind::TaskManager:
      return "task-manager";
    case FleetKind::Sim:
      return "sim";
    case FleetKind::MocapRelay:
      return "mocap-relay";
    case FleetKind::Process:
      break;
  }
  return "process";
}

FleetView::FleetView(double manager_query_period_s)
    : manager_query_period_s_(manager_query_period_s) {}

FleetView::Entry& FleetView::status_entry(FleetKind kind, std::int64_t id, std::int64_t at_ns) {
  Entry& e = entries_[Key{kind, id, ""}];
  if (e.first_ns < 0) e.first_ns = at_ns;
  e.status_ns = std::max(e.status_ns, at_ns);
  ++e.messages;
  return e;
}

void FleetView::heard(const msg::UavStatus& s, nlohmann::ordered_json json, std::int64_t at_ns) {
  Entry& e = status_entry(FleetKind::UavAgent, s.uav_id, at_ns);
  e.state = uav_state(s);
  e.failsafe = lower_after(msg::to_string(s.failsafe), "FAILSAFE_");
  e.task = s.task_id.empty() ? "-" : s.task_id;
  e.detail = std::move(json);
}

void FleetView::heard(const msg::FcState& s, nlohmann::ordered_json json, std::int64_t at_ns) {
  Entry& e = status_entry(FleetKind::FcBridge, s.uav_id, at_ns);
  e.state = !s.link_ok ? "link LOST" : s.offboard_ready ? "offboard-ready" : "link up";
  e.failsafe = s.failsafe.empty() ? "none" : s.failsafe;
  e.autopilot = autopilot_summary(s);
  e.detail = std::move(json);
}

void FleetView::heard(const msg::UgvStatus& s, nlohmann::ordered_json json, std::int64_t at_ns) {
  Entry& e = status_entry(FleetKind::UgvAgent, s.ugv_id, at_ns);
  char rate[64];
  std::snprintf(rate, sizeof rate, ", IMU %.0f Hz", s.imu_rate_hz);
  e.state = std::string(s.healthy ? "healthy" : "UNHEALTHY") + rate +
            (s.source.empty() ? "" : " (" + s.source + ")");
  e.detail = std::move(json);
}

void FleetView::heard(const msg::SimClock& s, nlohmann::ordered_json json, std::int64_t at_ns) {
  Entry& e = status_entry(FleetKind::Sim, -1, at_ns);
  e.state = lower_after(msg::to_string(s.mode), "CLOCK_MODE_") + ", t " +
            seconds(static_cast<double>(s.stamp_ns) / kNsPerS) + " s";
  e.detail = std::move(json);
}

void FleetView::heard(const msg::ManagerReply& reply, nlohmann::ordered_json json,
                      std::int64_t at_ns) {
  Entry& e = status_entry(FleetKind::TaskManager, -1, at_ns);
  e.state = manager_state(reply, e.task);
  e.detail = std::move(json);
}

void FleetView::heard_peer(const std::string& name, std::int64_t at_ns) {
  const std::size_t slash = name.rfind('/');
  const std::string process = slash == std::string::npos ? name : name.substr(slash + 1);
  Key key{FleetKind::Process, -1, name};
  for (const NamedKind& named : kNamedKinds) {
    if (process.rfind(named.prefix, 0) != 0) continue;
    const std::string rest = process.substr(named.prefix.size());
    if (!named.numbered && rest.empty()) key = Key{named.kind, -1, name};
    const bool decimal =
        !rest.empty() && rest.size() <= 9 && std::all_of(rest.begin(), rest.end(), [](char c) {
          return std::isdigit(static_cast<unsigned char>(c));
        });
    if (named.numbered && decimal) key = Key{named.kind, std::stoll(rest), ""};
  }
  Entry& e = entries_[key];
  if (e.first_ns < 0) e.first_ns = at_ns;
  e.peer_ns = std::max(e.peer_ns, at_ns);
  ++e.messages;
  e.processes.insert(name);
}

void FleetView::discovered(FleetKind kind, std::optional<std::uint32_t> id, std::int64_t at_ns) {
  Entry& e = entries_[Key{kind, id ? static_cast<std::int64_t>(*id) : -1, ""}];
  if (e.first_ns < 0) e.first_ns = at_ns;
}

// Its status heard; a kind with none to hear (a process known only by its clock requests)
// is described by its name.
bool FleetView::described(FleetKind kind, const Entry& entry) {
  return entry.status_ns >= 0 || kind == FleetKind::MocapRelay || kind == FleetKind::Process;
}

bool FleetView::settled(std::int64_t now_ns, std::int64_t naming_grace_ns) const {
  for (const auto& [key, entry] : merged()) {
    if (!described(std::get<0>(key), entry)) return false;
    if (entry.processes.empty() && now_ns - entry.first_ns < naming_grace_ns) return false;
  }
  return true;
}

// A status without a name (the simulator's clock, the task manager's reply) belongs to the
// one process of its kind named in the clock exchange; with none or several, it stays a
// row of its own.
std::map<FleetView::Key, FleetView::Entry> FleetView::merged() const {
  std::map<Key, Entry> out = entries_;
  for (auto it = out.begin(); it != out.end();) {
    const auto& [kind, id, name] = it->first;
    if (has_id(kind) || !name.empty()) {
      ++it;
      continue;
    }
    std::vector<Entry*> named;
    for (auto& [key, entry] : out) {
      if (std::get<0>(key) == kind && !std::get<2>(key).empty()) named.push_back(&entry);
    }
    if (named.size() != 1) {
      ++it;
      continue;
    }
    Entry& target = *named.front();
    const Entry& anonymous = it->second;
    target.status_ns = std::max(target.status_ns, anonymous.status_ns);
    target.first_ns = std::min(target.first_ns, anonymous.first_ns);
    target.messages += anonymous.messages;
    target.state = anonymous.state;
    target.failsafe = anonymous.failsafe;
    target.task = anonymous.task;
    target.detail = anonymous.detail;
    it = out.erase(it);
  }
  return out;
}

FleetRow FleetView::row(const Key& key, const Entry& e, std::int64_t now_ns) const {
  FleetRow r;
  r.kind = std::get<0>(key);
  if (std::get<1>(key) >= 0) r.id = static_cast<std::uint32_t>(std::get<1>(key));
  r.processes.assign(e.processes.begin(), e.processes.end());
  // A vehicle's age is its status's: an agent whose loop hung may still answer clocks.
  // The task manager has no status of its own: its clock requests count as much.
  // Discovered and nothing heard yet: since its discovery.
  const bool status_heard = e.status_ns >= 0;
  const std::int64_t last = r.kind == FleetKind::TaskManager || !status_heard
                                ? std::max({e.status_ns, e.peer_ns, e.first_ns})
                                : e.status_ns;
  r.age_s = static_cast<double>(std::max<std::int64_t>(0, now_ns - last)) / kNsPerS;
  r.stale_after_s = stale_after_s(r.kind, status_heard, manager_query_period_s_);
  r.stale = r.age_s > r.stale_after_s;
  r.messages = e.messages;
  r.state = !e.state.empty()                   ? e.state
            : described(r.kind, e)             ? "heard in the clock exchange only"
            : r.kind == FleetKind::TaskManager ? "still listening: no answer to the query yet"
                                               : "still listening: no status heard yet";
  r.failsafe = e.failsafe;
  r.task = e.task;
  r.autopilot = e.autopilot;
  r.detail = e.detail;
  return r;
}

std::vector<FleetRow> FleetView::rows(std::int64_t now_ns) const {
  const std::map<Key, Entry> all = merged();
  std::vector<FleetRow> out;
  for (const auto& [key, entry] : all) out.push_back(row(key, entry, now_ns));
  // A UAV agent's row shows its autopilot as its bridge reports it.
  for (FleetRow& r : out) {
    if (r.kind != FleetKind::UavAgent) continue;
    for (const FleetRow& bridge : out) {
      if (bridge.kind == FleetKind::FcBridge && bridge.id == r.id) {
        r.autopilot = bridge.autopilot + (bridge.stale ? " (bridge stale)" : "");
      }
    }
  }
  return out;
}

std::string fleet_table(const std::vector<FleetRow>& rows) {
  std::vector<std::array<std::string, 8>> cells{
      {"KIND", "ID", "PROCESS", "AGE", "STATE", "FAILSAFE", "TASK", "AUTOPILOT"}};
  for (const FleetRow& r : rows) {
    std::string processes;
    for (const std::string& p : r.processes) processes += (processes.empty() ? "" : ", ") + p;
    cells.push_back({kind_name(r.kind), r.id ? std::to_string(*r.id) : "-",
                     processes.empty() ? "?" : processes,
                     seconds(r.age_s) + " s" + (r.stale ? " STALE" : ""), r.state, r.failsafe,
                     r.task, r.autopilot});
  }
  std::array<std::size_t, 8> width{};
  for (const auto& line : cells) {
    for (std::size_t c = 0; c < line.size(); ++c) width[c] = std::max(width[c], line[c].size());
  }
  std::string text;
  for (const auto& line : cells) {
    std::string out;
    for (std::size_t c = 0; c < line.size(); ++c) {
      out += line[c];
      if (c + 1 < line.size()) out += std::string(width[c] - line[c].size() + 2, ' ');
    }
    while (!out.empty() && out.back() == ' ') out.pop_back();
    text += out + "\n";
  }
  return text;
}

nlohmann::ordered_json fleet_json(const std::vector<FleetRow>& rows) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const FleetRow& r : rows) {
    nlohmann::ordered_json j;
    j["kind"] = kind_name(r.kind);
    j["id"] = r.id ? nlohmann::ordered_json(*r.id) : nlohmann::ordered_json(nullptr);
    j["processes"] = r.processes;
    j["age_s"] = r.age_s;
    j["stale"] = r.stale;
    j["stale_after_s"] = r.stale_after_s;
    j["messages"] = r.messages;
    j["state"] = r.state;
    j["failsafe"] = r.failsafe;
    j["task"] = r.task;
    j["autopilot"] = r.autopilot;
    j["last"] = r.detail;
    list.push_back(std::move(j));
  }
  return list;
}

}  // namespace cover::cli
