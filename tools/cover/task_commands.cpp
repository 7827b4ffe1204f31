#include "task_commands.hpp"

#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <thread>

#include "cover/clock/clock.hpp"
#include "cover/config/config_error.hpp"
#include "cover/dds/json_codec.hpp"
#include "cover/mission/task_file.hpp"
#include "cover/process/shutdown_signal.hpp"
#include "cover/vocabulary/fleet_size.hpp"
#include "cover/vocabulary/task.hpp"
#include "cover/wire/task.hpp"
#include "manager_client.hpp"

namespace cover::cli {
namespace {

using namespace std::chrono_literals;

bool is_final(msg::ManagedTaskState s) {
  using S = msg::ManagedTaskState;
  return s == S::MANAGED_SUCCEEDED || s == S::MANAGED_FAILED || s == S::MANAGED_ABORTED ||
         s == S::MANAGED_REJECTED;
}

// "MANAGED_RUNNING" -> "running"
std::string state_name(msg::ManagedTaskState s) {
  std::string name = msg::to_string(s);
  name = name.substr(name.find('_') + 1);
  for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return name;
}

void print_record(const msg::ManagedTask& t) {
  std::printf("%-24s UAV %-2u %-10s #%-5lld %s\n", t.task_id.c_str(), t.uav_id,
              state_name(t.state).c_str(), static_cast<long long>(t.queue_position),
              t.reason.c_str());
}

int print_reply(const msg::ManagerReply& reply, const TaskCommandOptions& options) {
  if (options.json) {
    std::cout << dds::to_json(reply).dump() << std::endl;
  } else {
    if (!reply.message.empty()) std::cout << reply.message << "\n";
    for (const auto& t : reply.tasks) print_record(t);
  }
  return reply.ok ? kTaskOk : kTaskRefused;
}

// Runs `body` with a client; turns the failures every command shares into exit codes.
template <typename Body>
int with_client(const dds::ParticipantOptions& dds, const TaskCommandOptions& options, Body body) {
  try {
    dds::Participant participant(dds);
    ManagerClient client(participant, clock::to_milliseconds(options.timeout_s));
    return body(client);
  } catch (const ManagerUnreachable& e) {
    std::cerr << "cover: " << e.what() << "\n";
    return kTaskNoManager;
  }
}

msg::ManagerRequest query_of(const std::string& task_id) {
  msg::ManagerRequest request;
  request.kind = msg::ManagerRequestKind::MANAGER_QUERY;
  request.task_id = task_id;
  return request;
}

// One line of the watch: the manager's record and the UAV's live status.
std::string watch_line(const msg::ManagedTask& t, const std::optional<msg::UavStatus>& s) {
  char line[512];
  if (!s || s->task_id != t.task_id) {
    std::snprintf(line, sizeof line, "%s  UAV %u  %s  %s", t.task_id.c_str(), t.uav_id,
                  state_name(t.state).c_str(), t.reason.c_str());
    return line;
  }
  std::string stage = msg::to_string(s->stage);
  std::string failsafe = msg::to_string(s->failsafe);
  std::snprintf(line, sizeof line,
                "%s  UAV %u  %s  process %u/%u  %s  %.2f m to go  %.2f m/s  solver %.0f us  "
                "failsafe %s",
                t.task_id.c_str(), t.uav_id, state_name(t.state).c_str(), s->process_index + 1,
                s->process_count, stage.substr(stage.find('_') + 1).c_str(),
                s->distance_to_stage_point_m, s->speed_m_s, s->solve_time_us,
                failsafe.substr(failsafe.find('_') + 1).c_str());
  return line;
}

int follow(ManagerClient& client, const std::string& task_id, const TaskCommandOptions& options) {
  const bool terminal = isatty(STDOUT_FILENO) != 0 && !options.json;
  std::optional<dds::Reader<msg::UavStatus>> uav_reader;
  std::string last_line;
  while (!process::ShutdownSignal::requested()) {
    const msg::ManagerReply reply = client.call(query_of(task_id));
    if (!reply.ok || reply.tasks.empty()) return print_reply(reply, options);
    const msg::ManagedTask& t = reply.tasks.front();
    if (!uav_reader)
      uav_reader = client.participant().make_reader(dds::topics::uav_status(t.uav_id));
    const auto live = uav_reader->latest();
    const std::string line =
        watch_line(t, live ? std::optional<msg::UavStatus>(live->sample) : std::nullopt);
    if (line != last_line) {
      if (options.json) {
        nlohmann::json j = dds::to_json(t);
        if (live) j["uav_status"] = dds::to_json(live->sample);
        std::cout << j.dump() << std::endl;
      } else if (terminal) {
        std::cout << "\r\033[K" << line << std::flush;
      } else {
        std::cout << line << std::endl;
      }
      last_line = line;
    }
    if (is_final(t.state)) {
      if (terminal) std::cout << "\n";
      return t.state == msg::ManagedTaskState::MANAGED_SUCCEEDED ? kTaskOk : kTaskRefused;
    }
    process::ShutdownSignal::wait_for(200ms);
  }
  return 130;
}

}  // namespace

int submit(const dds::ParticipantOptions& dds, const TaskCommandOptions& options,
           const SubmitRequest& request) {
  mission::Task task;
  try {
    // Any UGV of the fleet may be named; the manager checks that it is up.
    task = mission::load_task_file(request.file, fleet::kMaxUgvs);
    if (request.uav >= 0) task.uav_id = request.uav;
  } catch (const config::ConfigError& e) {
    std::cerr << "cover submit: " << e.what() << "\n";
    return kTaskBadInput;
  }
  return with_client(dds, options, [&](ManagerClient& client) {
    msg::ManagerRequest r;
    r.kind = msg::ManagerRequestKind::MANAGER_SUBMIT;
    r.task = wire::to_msg(task, 0.0);
    // "waiting for UGV 7 (not heard yet ...)" at once, then the decision.
    const auto interim = [&](const msg::ManagerReply& held) {
      if (options.json) {
        std::cout << dds::to_json(held).dump() << std::endl;
      } else {
        std::cout << held.message << std::endl;
      }
    };
    const msg::ManagerReply reply = client.call(r, interim);
    const int code = print_reply(reply, options);
    if (code != kTaskOk || !request.wait) return code;
    return follow(client, task.task_id, options);
  });
}

int list_tasks(const dds::ParticipantOptions& dds, const TaskCommandOptions& options, bool all) {
  return with_client(dds, options, [&](ManagerClient& client) {
    msg::ManagerRequest r = query_of("");
    r.include_final = all;
    const msg::ManagerReply reply = client.call(r);
    if (reply.ok && reply.tasks.empty() && !options.json) {
      std::cout << (all ? "no task (none was ever submitted to this task manager)"
                        : "no task queued or in flight (--all also lists the ended ones)")
                << std::endl;
      return kTaskOk;
    }
    return print_reply(reply, options);
  });
}

int task_status(const dds::ParticipantOptions& dds, const TaskCommandOptions& options,
                const std::string& task_id) {
  return with_client(dds, options, [&](ManagerClient& client) {
    return print_reply(client.call(query_of(task_id)), options);
  });
}

int watch(const dds::ParticipantOptions& dds, const TaskCommandOptions& options,
          const std::string& task_id) {
  return with_client(dds, options,
                     [&](ManagerClient& client) { return follow(client, task_id, options); });
}

int abort_task(const dds::ParticipantOptions& dds, const TaskCommandOptions& options,
               const std::string& task_id, const std::string& reason) {
  return with_client(dds, options, [&](ManagerClient& client) {
    msg::ManagerRequest r;
    r.kind = msg::ManagerRequestKind::MANAGER_ABORT;
    r.task_id = task_id;
    r.reason = reason;
    return print_reply(client.call(r), options);
  });
}

}  // namespace cover::cli
