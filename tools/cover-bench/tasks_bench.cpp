// cover-bench tasks: the task manager in a standing lockstep system (config/launch/
// system.yaml through cover-launch): submit-to-accepted latency as a ground station sees it,
// and tasks per second through the queue of trivial tasks (short hops between two UGVs).
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "bench_cli.hpp"
#include "bench_registry.hpp"
#include "bench_stats.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/dds/participant.hpp"
#include "cover/process/child_process.hpp"
#include "cover/wire/task.hpp"
#include "cover_binary.hpp"
#include "manager_client.hpp"
#include "not_measured.hpp"

namespace {

using namespace std::chrono_literals;
namespace msg = cover::msg;

const std::string kLaunch = cover::bench::cover_binary("cover-launch");

cover::mission::Task hop(const std::string& id, int from, int to) {
  cover::mission::Task task;
  task.task_id = id;
  cover::mission::TransitionProcess p;
  p.from_ugv = from;
  p.to_ugv = to;
  p.initial_point_m = {0, 0, 1.0};
  p.transition_point_m = {0, 0, 1.0};
  p.final_point_m = {0, 0, 1.0};
  p.vmax_m_s = 1.5;
  task.processes.push_back(p);
  return task;
}

msg::ManagerRequest submission(const cover::mission::Task& task) {
  msg::ManagerRequest r;
  r.kind = msg::ManagerRequestKind::MANAGER_SUBMIT;
  r.task = cover::wire::to_msg(task, 0.0);
  return r;
}

int finished(cover::cli::ManagerClient& client, int* succeeded) {
  msg::ManagerRequest r;
  r.kind = msg::ManagerRequestKind::MANAGER_QUERY;
  r.include_final = true;
  int count = 0;
  *succeeded = 0;
  for (const auto& t : client.call(r).tasks) {
    using S = msg::ManagedTaskState;
    if (t.state == S::MANAGED_SUCCEEDED) ++*succeeded;
    if (t.state != S::MANAGED_QUEUED && t.state != S::MANAGED_DISPATCHED &&
        t.state != S::MANAGED_RUNNING) {
      ++count;
    }
  }
  return count;
}

int run(const std::vector<std::string>& args) {
  CLI::App app{"The task manager: submit-to-accepted latency and tasks per second (lockstep)"};
  bool json = false;
  int tasks = 40;
  int domain = 190;
  app.add_flag("--json", json, "print JSON instead of a table");
  app.add_option("--tasks", tasks, "trivial tasks pushed through the queue (>= 1)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--domain", domain, "DDS domain of the system")->capture_default_str();
  if (int rc = cover::bench::parse_args(app, args); rc >= 0) return rc;

  const auto dir =
      std::filesystem::temp_directory_path() / ("cover_tasks_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  cover::process::SpawnOptions options;
  options.log_file = (dir / "launcher.log").string();
  cover::process::ChildProcess system(
      {kLaunch, cover::config::default_config_dir() + "/launch/system.yaml", "--domain",
       std::to_string(domain), "--run-dir", (dir / "run").string(), "--var",
       "db=" + (dir / "tasks.db").string()},
      options);
  cover::dds::ParticipantOptions participant_options;
  participant_options.domain_id = domain;
  nlohmann::json out;
  cover::bench::NotMeasured missing;
  {
    cover::dds::Participant station(participant_options);
    cover::cli::ManagerClient client(station, 10s);
    // Warm-up: the system starts and the manager listens to its fleet first.
    bool up = false;
    for (int attempt = 0; attempt < 20 && !up; ++attempt) {
      try {
        up = client.call(submission(hop("warm-up", 0, 1))).ok;
      } catch (const cover::cli::ManagerUnreachable&) {
      }
    }
    if (!up) {
      std::cerr << "cover-bench tasks: the system did not come up; see " << dir << "\n";
      return 1;
    }
    std::vector<double> accept_ms;
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < tasks; ++i) {
      const auto t0 = std::chrono::steady_clock::now();
      const msg::ManagerReply reply =
          client.call(submission(hop("hop" + std::to_string(i), 1 - i % 2, i % 2)));
      const double ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      if (reply.ok) {
        accept_ms.push_back(ms);  // a refusal is no submit-to-accepted latency
      } else {
        std::cerr << "hop" << i << ": " << reply.message << "\n";
      }
    }
    int succeeded = 0;
    int done = 0;
    const auto deadline = start + 600s;
    while ((done = finished(client, &succeeded)) < tasks + 1 &&
           std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(50ms);  // polling pace of a ground station, not a synchronisation
    }
    const double elapsed_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const int hops_done = done - 1;  // the warm-up task is one of them
    if (accept_ms.empty()) missing.add("accept latency: the manager accepted none of the tasks");
    if (hops_done <= 0) missing.add("throughput: no task finished within 600 s");
    out = {{"tasks", tasks},
           {"finished", std::max(hops_done, 0)},
           {"succeeded", std::max(succeeded - 1, 0)},
           {"accepted", accept_ms.size()},
           {"accept_p50_ms", cover::bench::figure_json(cover::bench::percentile(accept_ms, 0.5))},
           {"accept_p99_ms", cover::bench::figure_json(cover::bench::percentile(accept_ms, 0.99))},
           {"tasks_per_s", cover::bench::figure_json(hops_done > 0 ? hops_done / elapsed_s : NAN)}};
  }
  system.terminate(20s, SIGINT);
  std::filesystem::remove_all(dir);
  if (json) {
    std::cout << out.dump(2) << "\n";
  } else {
    std::printf("task manager, standing lockstep system (config/launch/system.yaml)\n");
    const auto text = [&](const char* key, const char* format) {
      return cover::bench::figure_text(format, out[key].is_number() ? out[key].get<double>() : NAN);
    };
    std::printf("  submit -> accepted   p50 %s, p99 %s (%zu of %d submissions accepted)\n",
                text("accept_p50_ms", "%.2f ms").c_str(), text("accept_p99_ms", "%.2f ms").c_str(),
                out["accepted"].get<std::size_t>(), tasks);
    std::printf("  throughput           %s (%d finished, %d of %d succeeded)\n",
                text("tasks_per_s", "%.2f tasks/s").c_str(), out["finished"].get<int>(),
                out["succeeded"].get<int>(), tasks);
  }
  return missing.exit_code("tasks");
}

const cover::bench::Registrar registrar{"tasks",
                                        "task manager: accept latency and tasks per second", &run};

}  // namespace
