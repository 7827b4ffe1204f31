// cover-bench respawn: can a respawn rescue a flight? The standing system (config/launch/
// system.yaml, realtime) flies hops between G0 and G1, each from the deck the UAV is on;
// half a second into each transition stage the agent of the UGV whose IMU the UAV then
// flies on (the hop's to_ugv) is SIGKILLed. Per try: when the launcher
// restarted it, when it published its first sample, when a Fast DDS and a Cyclone DDS reader
// that were running all along heard it again, what the UAV agent's failsafe ladder did and
// how the task ended (docs/failsafes.md, "A sensor agent's restart").
#include <signal.h>
#include <time.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bench_cli.hpp"
#include "bench_registry.hpp"
#include "bench_stats.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/dds/domain_claim.hpp"
#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/process/child_process.hpp"
#include "cover/wire/enums.hpp"
#include "cover/wire/task.hpp"
#include "cover_binary.hpp"
#include "manager_client.hpp"
#include "not_measured.hpp"

namespace {

using namespace std::chrono_literals;
namespace msg = cover::msg;
using Clock = std::chrono::steady_clock;

const std::string kLaunch = cover::bench::cover_binary("cover-launch");

constexpr auto kIntoTransition = 500ms;  // when the kill lands
constexpr auto kTaskTimeout = 60s;

// A reader that was running before the kill, as the UAV agent's is: when it first hears the
// restarted agent (its IMU sequence starts over).
class RestartEar {
 public:
  RestartEar(cover::dds::Participant& participant, std::uint32_t ugv)
      : reader_(participant.make_reader(cover::dds::topics::ugv_imu(ugv),
                                        [this](const msg::UgvImu& sample) { hear(sample); })) {}
  void arm() {
    std::lock_guard<std::mutex> lock(mutex_);
    heard_.reset();
    armed_ = true;
  }
  std::optional<Clock::time_point> heard() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return heard_;
  }

 private:
  void hear(const msg::UgvImu& sample) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (armed_ && last_seq_ && sample.seq < *last_seq_) {
      heard_ = Clock::now();
      armed_ = false;
    }
    last_seq_ = sample.seq;
  }
  mutable std::mutex mutex_;
  bool armed_ = false;
  std::optional<std::uint32_t> last_seq_;
  std::optional<Clock::time_point> heard_;
  cover::dds::Reader<msg::UgvImu> reader_;
};

// The UAV agent's control trace: its ladder's changes, and when the transition stage began.
class LadderWatch {
 public:
  struct Change {
    Clock::time_point at;
    msg::FailsafeState failsafe;
  };
  explicit LadderWatch(cover::dds::Participant& participant)
      : reader_(participant.make_reader(cover::dds::topics::uav_trace(0),
                                        [this](const msg::ControlTrace& step) { see(step); })) {}
  void reset() {
    std::lock_guard<std::mutex> lock(mutex_);
    transition_since_.reset();
  }
  std::optional<Clock::time_point> transition_since() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return transition_since_;
  }
  std::uint32_t reference_ugv() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return reference_ugv_;
  }
  std::vector<Change> changes_since(Clock::time_point since) const {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<Change> out;
    for (const auto& change : changes_) {
      if (change.at >= since) out.push_back(change);
    }
    return out;
  }

 private:
  void see(const msg::ControlTrace& step) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (changes_.empty() || changes_.back().failsafe != step.failsafe) {
      changes_.push_back({Clock::now(), step.failsafe});
    }
    if (step.stage == msg::Stage::STAGE_TRANSITION && !transition_since_) {
      transition_since_ = Clock::now();
    }
    reference_ugv_ = step.reference_ugv;
  }
  mutable std::mutex mutex_;
  std::vector<Change> changes_;
  std::optional<Clock::time_point> transition_since_;
  std::uint32_t reference_ugv_ = 0;
  cover::dds::Reader<msg::ControlTrace> reader_;
};

cover::dds::ParticipantOptions participant_options(cover::dds::Vendor vendor, int domain) {
  cover::dds::ParticipantOptions options;
  options.vendor = vendor;
  options.domain_id = domain;
  return options;
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream stream(path);
  std::stringstream text;
  text << stream.rdbuf();
  return text.str();
}

// Milliseconds since local midnight of a log line's "HH:MM:SS.mmm" (the launcher's lines
// start with a date first); nullopt when `line` has none.
std::optional<double> time_of_day_ms(const std::string& line) {
  static const std::regex stamp(R"((\d\d):(\d\d):(\d\d)\.(\d\d\d))");
  std::smatch match;
  if (!std::regex_search(line, match, stamp)) return std::nullopt;
  return ((std::stod(match[1]) * 60 + std::stod(match[2])) * 60 + std::stod(match[3])) * 1e3 +
         std::stod(match[4]);
}

double time_of_day_ms(std::chrono::system_clock::time_point at) {
  const std::time_t seconds = std::chrono::system_clock::to_time_t(at);
  std::tm local{};
  localtime_r(&seconds, &local);
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(at.time_since_epoch()) %
                  std::chrono::seconds(1);
  return ((local.tm_hour * 60.0 + local.tm_min) * 60.0 + local.tm_sec) * 1e3 +
         static_cast<double>(ms.count());
}

// The last line of `text` containing `marker`, or "".
std::string last_line_with(const std::string& text, const std::string& marker) {
  std::string found;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.find(marker) != std::string::npos) found = line;
  }
  return found;
}

// The pid of the latest start of process `name` in launch.log; -1 when none yet.
int latest_pid(const std::string& launch_log, const std::string& name) {
  const std::string line = last_line_with(launch_log, "started " + name + " pid ");
  if (line.empty()) return -1;
  return std::stoi(line.substr(line.find(" pid ") + 5));
}

bool wait_until(const std::function<bool()>& condition, Clock::duration timeout) {
  const auto deadline = Clock::now() + timeout;
  while (!condition()) {
    if (Clock::now() >= deadline) return false;
    std::this_thread::sleep_for(5ms);  // polling pace of a condition, not a synchronisation
  }
  return true;
}

msg::ManagerRequest hop_submission(const std::string& id, int from, int to) {
  cover::mission::Task task;
  task.task_id = id;
  cover::mission::TransitionProcess hop;
  hop.from_ugv = from;
  hop.to_ugv = to;
  hop.initial_point_m = {0, 0, 1.0};
  hop.transition_point_m = {0, 0, 1.0};
  hop.final_point_m = {0, 0, 0.05};
  hop.final_action = cover::mission::FinalAction::Land;
  hop.vmax_m_s = 1.5;
  task.processes.push_back(hop);
  msg::ManagerRequest request;
  request.kind = msg::ManagerRequestKind::MANAGER_SUBMIT;
  request.task = cover::wire::to_msg(task, 0.0);
  return request;
}

// The task's record once it has ended; nullopt while it runs or on no answer.
std::optional<msg::ManagedTask> ended(cover::cli::ManagerClient& client, const std::string& id) {
  msg::ManagerRequest query;
  query.kind = msg::ManagerRequestKind::MANAGER_QUERY;
  query.task_id = id;
  try {
    for (const auto& task : client.call(query).tasks) {
      using S = msg::ManagedTaskState;
      if (task.task_id == id && task.state != S::MANAGED_QUEUED &&
          task.state != S::MANAGED_DISPATCHED && task.state != S::MANAGED_RUNNING) {
        return task;
      }
    }
  } catch (const cover::cli::ManagerUnreachable&) {
  }
  return std::nullopt;
}

std::string failsafe_name(msg::FailsafeState state) {
  const auto failsafe = cover::wire::from_msg(state);
  return failsafe ? cover::mission::to_string(*failsafe) : "unknown";
}

double ms_between(Clock::time_point from, std::optional<Clock::time_point> to) {
  return to ? std::chrono::duration<double, std::milli>(*to - from).count() : NAN;
}

nlohmann::json number_or_null(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

struct System {
  std::filesystem::path dir;
  int domain = 0;
  std::unique_ptr<cover::process::ChildProcess> launcher;
  std::string launch_log() const { return read_text(dir / "run" / "launch.log"); }
  std::string log_of(const std::string& name) const {
    return read_text(dir / "run" / (name + ".log"));
  }
};

class RespawnBench {
 public:
  RespawnBench(System& system, cover::dds::Participant& fastdds, cover::dds::Participant& cyclone)
      : system_(system),
        fastdds_ears_{RestartEar(fastdds, 0), RestartEar(fastdds, 1)},
        cyclone_ears_{RestartEar(cyclone, 0), RestartEar(cyclone, 1)},
        ladder_(cyclone),
        client_(cyclone, 10s) {}

  // Submits until the manager takes a task (the system is up and heard) and flies it; false
  // when that did not happen within a minute each.
  bool wait_for_system() {
    if (!wait_until([&] { return submit("warm-up"); }, 60s)) return false;
    const auto record = finish("warm-up");
    if (record && outcome_of(*record) == "succeeded") deck_ = 1 - deck_;
    return record.has_value();
  }

  // One hop with its kill; the row, or a row with "error".
  nlohmann::json try_once(int index) {
    const std::string id = "respawn-" + std::to_string(index);
    ladder_.reset();
    if (!submit(id)) return {{"try", index}, {"error", "the task manager took no task"}};
    const bool in_transition = wait_until(
        [&] {
          const auto since = ladder_.transition_since();
          return since && Clock::now() - *since >= kIntoTransition;
        },
        kTaskTimeout);
    const int target = 1 - deck_;
    if (!in_transition || static_cast<int>(ladder_.reference_ugv()) != target) {
      const auto record = finish(id);
      return {{"try", index},
              {"error", "the transition stage on G" + std::to_string(target) +
                            " never came; the task " +
                            (record ? outcome_of(*record) + ": " + record->reason
                                    : std::string("did not end"))}};
    }
    nlohmann::json row = kill_and_follow(index, id, target);
    if (row["task"] == "succeeded") deck_ = target;
    return row;
  }

 private:
  bool submit(const std::string& id) {
    try {
      return client_.call(hop_submission(id, deck_, 1 - deck_)).ok;
    } catch (const cover::cli::ManagerUnreachable&) {
      return false;
    }
  }

  std::optional<msg::ManagedTask> finish(const std::string& id) {
    std::optional<msg::ManagedTask> record;
    wait_until([&] { return (record = ended(client_, id)).has_value(); }, kTaskTimeout);
    return record;
  }

  // Kills UGV `ugv`'s agent and follows the task `id` to its end.
  nlohmann::json kill_and_follow(int index, const std::string& id, int ugv) {
    const std::string name = "ugv" + std::to_string(ugv);
    const int pid = latest_pid(system_.launch_log(), name);
    RestartEar& fastdds_ear = fastdds_ears_[ugv];
    RestartEar& cyclone_ear = cyclone_ears_[ugv];
    fastdds_ear.arm();
    cyclone_ear.arm();
    const auto killed = Clock::now();
    const double killed_ms = time_of_day_ms(std::chrono::system_clock::now());
    kill(pid, SIGKILL);
    const auto record = finish(id);
    nlohmann::json row = {{"try", index},
                          {"killed", name},
                          {"killed_pid", pid},
                          {"task", record ? outcome_of(*record) : "no answer"},
                          {"reason", record ? record->reason : ""}};
    const auto since_kill = [&](const std::string& text, const std::string& marker) {
      const auto at = time_of_day_ms(last_line_with(text, marker));
      return at ? *at - killed_ms : NAN;
    };
    row["restart_ms"] =
        number_or_null(since_kill(system_.launch_log(), "started " + name + " pid"));
    row["first_sample_ms"] = number_or_null(since_kill(system_.log_of(name), "first sample"));
    row["heard_fastdds_ms"] = number_or_null(ms_between(killed, fastdds_ear.heard()));
    row["heard_cyclone_ms"] = number_or_null(ms_between(killed, cyclone_ear.heard()));
    nlohmann::json ladder = nlohmann::json::array();
    for (const auto& change : ladder_.changes_since(killed)) {
      ladder.push_back(
          {{"state", failsafe_name(change.failsafe)}, {"at_ms", ms_between(killed, change.at)}});
    }
    row["ladder"] = ladder;
    return row;
  }

  static std::string outcome_of(const msg::ManagedTask& task) {
    return task.state == msg::ManagedTaskState::MANAGED_SUCCEEDED ? "succeeded" : "failed";
  }

  System& system_;
  // Per UGV (index k), on each vendor.
  RestartEar fastdds_ears_[2];
  RestartEar cyclone_ears_[2];
  int deck_ = 0;  // the UGV whose deck the UAV is on: the next hop starts there
  LadderWatch ladder_;
  cover::cli::ManagerClient client_;
};

std::string ms_text(const nlohmann::json& value) {
  if (!value.is_number()) return "    -";
  char text[16];
  std::snprintf(text, sizeof text, "%5.0f", value.get<double>());
  return text;
}

void print_table(const nlohmann::json& out) {
  std::printf(
      "respawn of the agent of the UGV the UAV flies to, killed %lld ms into the transition "
      "stage (config/launch/system.yaml, realtime%s)\n",
      static_cast<long long>(kIntoTransition.count()),
      out["flags"].empty() ? "" : (", " + out["flags"].dump()).c_str());
  std::printf(
      "try  killed  restart  1st sample  heard fastdds  heard cyclone  task       ladder (ms "
      "after the kill)\n");
  for (const auto& row : out["tries"]) {
    if (row.contains("error")) {
      std::printf("%3d  %s\n", row["try"].get<int>(), row["error"].get<std::string>().c_str());
      continue;
    }
    std::string ladder;
    for (const auto& change : row["ladder"]) {
      char step[64];
      std::snprintf(step, sizeof step, " %s@%.0f", change["state"].get<std::string>().c_str(),
                    change["at_ms"].get<double>());
      ladder += step;
    }
    std::printf("%3d  %-6s    %s       %s          %s          %s  %-9s %s\n",
                row["try"].get<int>(), row["killed"].get<std::string>().c_str(),
                ms_text(row["restart_ms"]).c_str(), ms_text(row["first_sample_ms"]).c_str(),
                ms_text(row["heard_fastdds_ms"]).c_str(), ms_text(row["heard_cyclone_ms"]).c_str(),
                row["task"].get<std::string>().c_str(), ladder.c_str());
  }
  std::printf(
      "heard again (ms after the kill): fastdds p50 %.0f max %.0f, cyclone p50 %.0f max "
      "%.0f; tasks succeeded %d of %d\n",
      out["heard_fastdds_p50_ms"].get<double>(), out["heard_fastdds_max_ms"].get<double>(),
      out["heard_cyclone_p50_ms"].get<double>(), out["heard_cyclone_max_ms"].get<double>(),
      out["succeeded"].get<int>(), out["measured"].get<int>());
}

// Summary over the rows that measured something; "measured" 0 when none did.
void summarise(nlohmann::json& out) {
  std::vector<double> fastdds, cyclone;
  int measured = 0, succeeded = 0;
  for (const auto& row : out["tries"]) {
    if (row.contains("error")) continue;
    ++measured;
    if (row["task"] == "succeeded") ++succeeded;
    if (row["heard_fastdds_ms"].is_number()) fastdds.push_back(row["heard_fastdds_ms"]);
    if (row["heard_cyclone_ms"].is_number()) cyclone.push_back(row["heard_cyclone_ms"]);
  }
  out["measured"] = measured;
  out["succeeded"] = succeeded;
  out["heard_fastdds_p50_ms"] = cover::bench::percentile(fastdds, 0.5);
  out["heard_fastdds_max_ms"] = cover::bench::percentile(fastdds, 1.0);
  out["heard_cyclone_p50_ms"] = cover::bench::percentile(cyclone, 0.5);
  out["heard_cyclone_max_ms"] = cover::bench::percentile(cyclone, 1.0);
}

std::vector<std::string> launcher_argv(const System& system,
                                       const std::vector<std::string>& flags) {
  std::vector<std::string> argv = {
      kLaunch,     cover::config::default_config_dir() + "/launch/system.yaml",
      "--domain",  std::to_string(system.domain),
      "--clock",   "realtime",
      "--run-dir", (system.dir / "run").string(),
      "--var",     "db=" + (system.dir / "tasks.db").string()};
  for (const auto& flag : flags) argv.insert(argv.end(), {"--dds", flag});
  return argv;
}

int run(const std::vector<std::string>& args) {
  CLI::App app{
      "Can a respawn rescue a flight: a UGV agent SIGKILLed mid-transition in the "
      "standing system (realtime), its restart timed and the task's end"};
  bool json = false;
  int tries = 5;
  int domain = 194;
  std::vector<std::string> dds;
  app.add_flag("--json", json, "print JSON instead of a table");
  app.add_option("--tries", tries, "kills, one per hop")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  app.add_option("--domain", domain, "DDS domain of the system")->capture_default_str();
  app.add_option("--dds", dds,
                 "NAME=VENDOR given to cover-launch (repeatable), e.g. uav0=fastdds to fly the "
                 "UAV agent on the other vendor");
  if (int rc = cover::bench::parse_args(app, args); rc >= 0) return rc;

  const auto claim = cover::dds::DomainClaim::claim(domain, std::chrono::minutes(30));
  System system;
  system.domain = claim.domain();
  system.dir =
      std::filesystem::temp_directory_path() / ("cover_respawn_" + std::to_string(getpid()));
  std::filesystem::create_directories(system.dir);
  cover::process::SpawnOptions options;
  options.log_file = (system.dir / "launcher.log").string();
  system.launcher =
      std::make_unique<cover::process::ChildProcess>(launcher_argv(system, dds), options);
  nlohmann::json out = {{"flags", dds}, {"tries", nlohmann::json::array()}};
  {
    cover::dds::Participant fastdds(
        participant_options(cover::dds::Vendor::FastDds, system.domain));
    cover::dds::Participant cyclone(
        participant_options(cover::dds::Vendor::Cyclone, system.domain));
    RespawnBench bench(system, fastdds, cyclone);
    if (!bench.wait_for_system()) {
      std::cerr << "cover-bench respawn: the system did not come up; see " << system.dir << "\n";
      return 1;
    }
    for (int i = 1; i <= tries; ++i) out["tries"].push_back(bench.try_once(i));
  }
  system.launcher->terminate(20s, SIGINT);
  summarise(out);
  if (out["measured"] == 0) {
    cover::bench::NotMeasured missing;
    missing.add("any restart: no try measured anything (see " + system.dir.string() + ")");
    return missing.exit_code("respawn");
  }
  std::filesystem::remove_all(system.dir);
  if (json) {
    std::cout << out.dump(2) << "\n";
  } else {
    print_table(out);
  }
  return 0;
}

const cover::bench::Registrar registrar{
    "respawn", "a UGV agent killed mid-flight: restart, first sample heard, task result", &run};

}  // namespace
