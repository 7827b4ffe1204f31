#include "station.hpp"

#include <spdlog/spdlog.h>
#include <sys/stat.h>

#include <csignal>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <ctime>

#include "cover/clock/clock.hpp"
#include "cover/dds/dds_error.hpp"
#include "cover/dds/json_codec.hpp"
#include "cover/process/shutdown_signal.hpp"
#include "cover/wire/task.hpp"
#include "fc_client.hpp"
#include "manager_client.hpp"

namespace cover::ground_station {
namespace {

using Json = nlohmann::json;
using namespace std::chrono_literals;

// Requests waiting for the worker beyond this are refused: a page cannot queue unbounded work.
constexpr std::size_t kMaxJobs = 32;
// Tasks listed on the page: the newest ones (the manager keeps every task ever submitted).
constexpr std::size_t kMaxTasksShown = 50;
// Points of a reference path sent to the page (the path is downsampled to this many).
constexpr std::size_t kMaxPathPoints = 60;
// A sample stamped within this of its arrival carries a wall-clock stamp (a field system, a
// realtime process on this host): the page may measure its latency from it. A simulated
// time (seconds since the run began) is not one.
constexpr std::int64_t kWallClockStampNs = 60'000'000'000;

Json xyz(const msg::Vector3& v) {
  return Json::array({v.x, v.y, v.z});
}

// "MANAGED_RUNNING" -> "running"
std::string lower_suffix(const std::string& name) {
  std::string s = name.substr(name.find('_') + 1);
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

msg::FcCommandKind fc_kind(FcCommand c) {
  switch (c) {
    case FcCommand::Arm:
      return msg::FcCommandKind::FC_COMMAND_ARM;
    case FcCommand::Offboard:
      return msg::FcCommandKind::FC_COMMAND_OFFBOARD;
    case FcCommand::Land:
      return msg::FcCommandKind::FC_COMMAND_LAND;
    case FcCommand::Disarm:
      return msg::FcCommandKind::FC_COMMAND_DISARM;
  }
  return msg::FcCommandKind::FC_COMMAND_LAND;
}

// The page shows each row's scalar fields; the bridge's parameter and stream lists (most
// of a row's bytes) are `cover fc check`'s, not sent ten times a second.
void drop_structured_fields(Json& row) {
  auto& last = row["last"];
  if (!last.is_object()) return;
  for (auto it = last.begin(); it != last.end();) {
    it = it->is_structured() ? last.erase(it) : std::next(it);
  }
}

}  // namespace

Station::Station(dds::Participant& participant, StationOptions options)
    : participant_(participant),
      options_(std::move(options)),
      listener_(participant, options_.fleet, options_.manager_query_period_s,
                [this](cli::FleetKind kind, std::optional<std::uint32_t> id, std::int64_t stamp) {
                  on_status(kind, id, stamp);
                }),
      world_(options_.dds_domain, options_.sim_run_id) {
  for (std::uint32_t u = 0; u < options_.fleet.uavs; ++u) {
    command_readers_.push_back(
        participant.make_reader(dds::topics::uav_command(u), [this, u](const msg::UavCommand& c) {
          std::lock_guard<std::mutex> lock(live_mutex_);
          live_[u].command = c;
        }));
    trace_readers_.push_back(
        participant.make_reader(dds::topics::uav_trace(u), [this, u](const msg::ControlTrace& t) {
          std::lock_guard<std::mutex> lock(live_mutex_);
          live_[u].trace = t;
        }));
    reference_readers_.push_back(participant.make_reader(
        dds::topics::uav_reference(u), [this, u](const msg::ReferenceTrajectory& r) {
          std::lock_guard<std::mutex> lock(live_mutex_);
          live_[u].reference = r;
        }));
    for (std::uint32_t k = 0; k < options_.fleet.ugvs; ++k) {
      relative_readers_.push_back(participant.make_reader(
          dds::topics::relative_state(u, k), [this, u, k](const msg::RelativeState& s) {
            std::lock_guard<std::mutex> lock(live_mutex_);
            live_[u].relative[k] = s;
          }));
    }
  }
  server_ = std::make_unique<WebServer>(
      options_.web, [this](std::uint64_t c, bool t, const std::string& m) { on_message(c, t, m); });
  worker_ = std::thread([this] { work(); });
  manager_thread_ = std::thread([this] { query_manager(); });
  push_thread_ = std::thread([this] { push_rows(); });
}

Station::~Station() {
  stopping_ = true;
  jobs_cv_.notify_all();
  {
    std::lock_guard<std::mutex> lock(push_mutex_);
    push_cv_.notify_all();
  }
  if (push_thread_.joinable()) push_thread_.join();
  if (worker_.joinable()) worker_.join();
  if (manager_thread_.joinable()) manager_thread_.join();
  server_->stop();
  std::lock_guard<std::mutex> lock(record_mutex_);
  if (recorder_) recorder_->terminate(5000ms, SIGINT);
}

// The simulator's clock (100 Hz) is no status: its row's age moves with the state rows.
void Station::on_status(cli::FleetKind kind, std::optional<std::uint32_t> id,
                        std::int64_t stamp_ns) {
  if (kind == cli::FleetKind::Sim) return;
  const std::int64_t now_ns = clock::system_ns();
  std::lock_guard<std::mutex> lock(push_mutex_);
  if (heard_.empty()) push_cv_.notify_one();
  heard_[{kind, id}] = {stamp_ns, now_ns};
}

// A row heard goes out at once when nothing went out in the last push_coalesce_ms, else at
// the end of that window with every row heard meanwhile (a burst, the same row again): a page
// gets at most one message per window, and a lone sample waits for none.
void Station::push_rows() {
  const auto window = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double, std::milli>(options_.push_coalesce_ms));
  auto last_push = std::chrono::steady_clock::now() - window;
  std::unique_lock<std::mutex> lock(push_mutex_);
  while (!stopping_) {
    push_cv_.wait(lock, [&] { return stopping_ || !heard_.empty(); });
    if (stopping_) return;
    push_cv_.wait_until(lock, last_push + window, [&] { return stopping_.load(); });
    std::map<RowKey, Heard> heard;
    heard.swap(heard_);
    lock.unlock();
    last_push = std::chrono::steady_clock::now();
    if (server_->stats().clients > 0) {
      const Json rows = rows_json(heard);
      if (!rows.empty()) {
        const Json message{{"type", "rows"}, {"rows", rows}};
        server_->broadcast(message.dump(-1, ' ', false, Json::error_handler_t::replace));
      }
    }
    lock.lock();
  }
}

// The rows heard that changed what the page shows of them (their text, or back from stale),
// as the state's fleet rows, each with the server's receive time and, when it is a wall-clock
// time, the sample's own stamp (milliseconds since the epoch). A sample that only moves its
// row's age (most of them: a UAV agent's 10 Hz status) waits for the next state.
Json Station::rows_json(const std::map<RowKey, Heard>& heard) {
  Json out = Json::array();
  for (const auto& row : listener_.rows()) {
    const RowKey key{row.kind, row.id};
    const auto it = heard.find(key);
    if (it == heard.end()) continue;
    std::string shown = row.state + '\n' + row.failsafe + '\n' + row.task + '\n' + row.autopilot;
    for (const std::string& process : row.processes) shown += '\n' + process;
    const auto before = pushed_heard_ns_.find(key);
    const bool was_stale =
        before == pushed_heard_ns_.end() ||
        static_cast<double>(it->second.received_ns - before->second) / 1e9 > row.stale_after_s;
    pushed_heard_ns_[key] = it->second.received_ns;
    std::string& pushed = pushed_shown_[key];
    if (!was_stale && pushed == shown) continue;
    pushed = std::move(shown);
    Json j = cli::fleet_json({row})[0];
    drop_structured_fields(j);
    const Heard& h = it->second;
    j["recv_ms"] = static_cast<double>(h.received_ns) / 1e6;
    if (std::llabs(h.received_ns - h.source_ns) < kWallClockStampNs)
      j["source_ms"] = static_cast<double>(h.source_ns) / 1e6;
    out.push_back(std::move(j));
  }
  return out;
}

void Station::on_message(std::uint64_t client, bool has_token, const std::string& text) {
  ApiRequest request = parse_request(text, static_cast<int>(options_.fleet.ugvs));
  if (request.op == ApiOp::Invalid) {
    server_->send(client, reply_json(request.id, false, request.error, request.field));
    return;
  }
  if (needs_token(request.op) && !has_token) {
    server_->send(client, reply_json(request.id, false,
                                     std::string(op_name(request.op)) +
                                         ": refused, this page was opened without the token "
                                         "(open the address printed at the station's start)"));
    return;
  }
  std::lock_guard<std::mutex> lock(jobs_mutex_);
  if (jobs_.size() >= kMaxJobs) {
    server_->send(client, reply_json(request.id, false, "busy: too many requests waiting"));
    return;
  }
  jobs_.push_back({client, std::move(request)});
  jobs_cv_.notify_one();
}

// The task manager's and the autopilots' answers can take seconds: one request at a time,
// off the server's I/O thread.
void Station::work() {
  make_clients();
  while (true) {
    Job job;
    {
      std::unique_lock<std::mutex> lock(jobs_mutex_);
      jobs_cv_.wait(lock, [&] { return stopping_ || !jobs_.empty(); });
      if (stopping_) return;
      job = std::move(jobs_.front());
      jobs_.pop_front();
    }
    bool ok = false;
    std::string field;
    std::string message;
    try {
      message = answer(job.request, ok, field);
    } catch (const std::exception& e) {
      message = e.what();
    }
    spdlog::info("{} {}: {}", op_name(job.request.op), ok ? "done" : "refused", message);
    server_->send(job.client, reply_json(job.request.id, ok, message, field));
  }
}

void Station::make_clients() {
  const auto timeout = clock::to_milliseconds(options_.command_timeout_s);
  try {
    manager_client_ = std::make_unique<cli::ManagerClient>(participant_, timeout);
  } catch (const dds::DdsError& e) {
    manager_client_error_ = e.what();
  }
  try {
    fc_client_ = std::make_unique<cli::FcClient>(participant_, timeout);
  } catch (const dds::DdsError& e) {
    fc_client_error_ = e.what();
  }
}

std::string Station::answer(const ApiRequest& request, bool& ok, std::string& field) {
  if (request.op == ApiOp::Record) return record(request.record_start, ok);
  if (request.op == ApiOp::Fc) {
    if (!fc_client_) return fc_client_error_;
    const auto reply = fc_client_->call(request.uav_id, fc_kind(request.fc));
    if (!reply)
      return "no answer: no flight-controller bridge for this UAV, or its autopilot is silent";
    ok = reply->result == msg::FcCommandResult::FC_RESULT_ACCEPTED;
    const char* result = ok                                                         ? "accepted"
                         : reply->result == msg::FcCommandResult::FC_RESULT_REFUSED ? "refused"
                                                                                    : "no answer";
    return std::string(result) + ": " + reply->message;
  }
  if (!manager_client_) return manager_client_error_;
  msg::ManagerRequest r;
  if (request.op == ApiOp::Submit) {
    r.kind = msg::ManagerRequestKind::MANAGER_SUBMIT;
    r.task = wire::to_msg(request.task, 0.0);
  } else {
    r.kind = msg::ManagerRequestKind::MANAGER_ABORT;
    r.task_id = request.task_id;
    r.reason = request.reason;
  }
  try {
    const msg::ManagerReply reply = manager_client_->call(r);
    ok = reply.ok;
    if (!ok) {
      field = field_of_error(reply.message);
      if (field.empty() && request.op == ApiOp::Submit) field = "task";
    }
    return reply.message;
  } catch (const cli::ManagerUnreachable& e) {
    return e.what();
  }
}

std::string Station::record(bool start, bool& ok) {
  std::lock_guard<std::mutex> lock(record_mutex_);
  if (!start) {
    if (!recorder_) return "no recording running";
    const int code = recorder_->terminate(10000ms, SIGINT);
    recorder_.reset();
    ok = code == 0;
    return "recording stopped: " + record_file_ +
           (ok ? "" : " (recorder exit " + std::to_string(code) + ")");
  }
  if (recorder_ && !recorder_->wait(0ms)) return "already recording to " + record_file_;
  if (options_.record_argv.empty()) return "no recorder: `cover` was not found beside this program";
  char name[64];
  const std::time_t now = std::time(nullptr);
  std::strftime(name, sizeof name, "/cover-%Y%m%d-%H%M%S.mcap", std::localtime(&now));
  record_file_ = options_.record_dir + name;
  auto argv = options_.record_argv;
  argv.insert(argv.end(), {"-o", record_file_});
  recorder_ = std::make_unique<process::ChildProcess>(argv);
  ok = true;
  return "recording to " + record_file_;
}

void Station::query_manager() {
  std::unique_ptr<cli::ManagerClient> client;
  try {
    client = std::make_unique<cli::ManagerClient>(
        participant_, clock::to_milliseconds(options_.manager_query_period_s * 2));
  } catch (const dds::DdsError& e) {
    // Under DDS-Security an identity without cover/manager/request (a viewer's station) may
    // not ask the task manager: the page shows why, the fleet and the autopilots still.
    spdlog::warn("no task list: {}", e.what());
    std::lock_guard<std::mutex> lock(tasks_mutex_);
    manager_note_ = e.what();
    return;
  }
  cli::ManagerClient& manager = *client;
  while (!stopping_) {
    msg::ManagerRequest query;
    query.kind = msg::ManagerRequestKind::MANAGER_QUERY;
    query.include_final = true;
    try {
      const msg::ManagerReply reply = manager.call(query);
      listener_.heard(reply);
      Json tasks = Json::array();
      const std::size_t first =
          reply.tasks.size() > kMaxTasksShown ? reply.tasks.size() - kMaxTasksShown : 0;
      for (std::size_t i = first; i < reply.tasks.size(); ++i) {
        const auto& t = reply.tasks[i];
        tasks.push_back({{"task_id", t.task_id},
                         {"uav_id", t.uav_id},
                         {"state", lower_suffix(msg::to_string(t.state))},
                         {"queue_position", t.queue_position},
                         {"reason", t.reason},
                         {"process_count", t.process_count}});
      }
      std::lock_guard<std::mutex> lock(tasks_mutex_);
      tasks_ = std::move(tasks);
      manager_note_ = "";
    } catch (const cli::ManagerUnreachable& e) {
      std::lock_guard<std::mutex> lock(tasks_mutex_);
      manager_note_ = e.what();
    }
    listener_.note_discoveries(manager);
    process::ShutdownSignal::wait_for(clock::to_milliseconds(options_.manager_query_period_s));
  }
}

Json Station::live_json() {
  Json live = Json::object();
  std::lock_guard<std::mutex> lock(live_mutex_);
  for (const auto& [u, l] : live_) {
    Json j;
    if (l.command) j["thrust_m_s2"] = l.command->thrust_m_s2;
    if (l.trace) {
      j["solve_time_us"] = l.trace->solve_time_us;
      j["reference_ugv"] = l.trace->reference_ugv;
      j["stage"] = lower_suffix(msg::to_string(l.trace->stage));
      const auto rel = l.relative.find(l.trace->reference_ugv);
      if (rel != l.relative.end()) {
        const auto& p = rel->second.position_m;
        const auto& r = l.trace->reference_position_m;
        j["tracking_error_m"] = std::sqrt((p.x - r.x) * (p.x - r.x) + (p.y - r.y) * (p.y - r.y) +
                                          (p.z - r.z) * (p.z - r.z));
      }
    }
    Json rel = Json::object();
    for (const auto& [k, s] : l.relative) {
      if (s.valid) rel[std::to_string(k)] = xyz(s.position_m);
    }
    j["relative"] = std::move(rel);
    if (l.reference && !l.reference->positions_m.empty()) {
      const auto& points = l.reference->positions_m;
      const std::size_t step = (points.size() + kMaxPathPoints - 1) / kMaxPathPoints;
      Json path = Json::array();
      for (std::size_t i = 0; i < points.size(); i += step) path.push_back(xyz(points[i]));
      path.push_back(xyz(points.back()));
      j["reference"] = {{"ugv", l.reference->reference_ugv}, {"points", std::move(path)}};
    }
    live[std::to_string(u)] = std::move(j);
  }
  return live;
}

Json Station::state_json() {
  Json state;
  state["type"] = "state";
  state["sent_ms"] = static_cast<double>(clock::system_ns()) / 1e6;
  state["fleet"] = cli::fleet_json(listener_.rows());
  for (auto& row : state["fleet"]) drop_structured_fields(row);
  {
    std::lock_guard<std::mutex> lock(tasks_mutex_);
    state["tasks"] = tasks_;
    state["manager"] = manager_note_;
  }
  state["live"] = live_json();
  state["world"] = world_.json();
  {
    std::lock_guard<std::mutex> lock(record_mutex_);
    if (recorder_ && recorder_->wait(0ms)) recorder_.reset();
    struct stat st {};
    const bool running = recorder_ != nullptr;
    state["recorder"] = {{"running", running},
                         {"file", record_file_},
                         {"bytes", !record_file_.empty() && ::stat(record_file_.c_str(), &st) == 0
                                       ? static_cast<double>(st.st_size)
                                       : 0.0}};
  }
  return state;
}

void Station::run() {
  const auto period = std::chrono::duration_cast<std::chrono::nanoseconds>(
      std::chrono::duration<double>(1.0 / options_.state_rate_hz));
  auto next = std::chrono::steady_clock::now();
  while (!process::ShutdownSignal::requested()) {
    if (server_->stats().clients > 0) {
      server_->broadcast(state_json().dump(-1, ' ', false, Json::error_handler_t::replace));
    }
    next += period;
    const auto now = std::chrono::steady_clock::now();
    if (next < now) next = now;
    process::ShutdownSignal::wait_for(
        std::chrono::duration_cast<std::chrono::milliseconds>(next - now));
  }
}

}  // namespace cover::ground_station
