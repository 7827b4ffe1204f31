#include "fleet_commands.hpp"

#include <unistd.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <iostream>
#include <mutex>
#include <set>
#include <tuple>
#include <vector>

#include "cover/clock/clock.hpp"
#include "cover/dds/json_codec.hpp"
#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/dds/vendor.hpp"
#include "cover/process/shutdown_signal.hpp"
#include "fleet_listener.hpp"
#include "fleet_view.hpp"
#include "manager_client.hpp"

namespace cover::cli {
namespace {

// How often a listing looks whether it may end.
constexpr std::chrono::milliseconds kListenStep{50};
// Fast DDS's announcement period when config/dds.yaml leaves announcement_period_s at 0.
// A Fast DDS process did not answer a new listener's announcements on loopback (measured:
// the simulator, the UAV agent and the task manager were discovered together 0.3 to 3.0 s
// after a listener started, at their next periodic announcement), so a first listing lasts
// one period: a process not discovered yet cannot be waited for by name.
constexpr double kFastDdsAnnouncementPeriod_s = 3.0;
// After the discovery: its endpoints matched within 0.1 s in those runs.
constexpr double kEndpointMatching_s = 0.5;
// The longest a first listing waits beyond that for the processes it heard to be described:
// two periods of the slowest message it relies on (UGV agents' status and the clock
// exchange, 1 Hz).
constexpr double kDescribeWait_s = 2.0;

}  // namespace

namespace {

// Asks the task manager for its tasks not ended; a fleet without one is no error.
msg::ManagerRequest manager_query() {
  msg::ManagerRequest request;
  request.kind = msg::ManagerRequestKind::MANAGER_QUERY;
  request.include_final = false;
  return request;
}

}  // namespace

FleetCommand::FleetCommand(CLI::App& app) {
  fleet_ = app.add_subcommand(
      "fleet",
      "Every vehicle and process heard on the domain: kind, id, host/process, age, state, "
      "failsafe, task, autopilot");
  fleet_
      ->add_option("--listen-s", listen_s_,
                   "seconds to listen at least (the slowest status, UGV agents' and the clock "
                   "exchange, comes once a second). The first listing lasts one DDS discovery "
                   "period at least (config/dds.yaml announcement_period_s + 0.5 s; Fast DDS "
                   "announces every 3 s when it is 0), then until every process heard is "
                   "described, up to 2 s more. --watch: the refresh period after it")
      ->check(CLI::Range(0.1, 600.0))
      ->capture_default_str();
  fleet_->add_flag("--watch", watch_, "list again every --listen-s until SIGINT/SIGTERM");
  fleet_->add_flag("--json", json_,
                   "one JSON document per listing (--watch: one per line) instead of a table");
  fleet_->add_option("--uavs", size_.uavs, "UAV ids 0..N-1 to listen for")->capture_default_str();
  fleet_->add_option("--ugvs", size_.ugvs, "UGV ids 0..N-1 to listen for")->capture_default_str();
  dds_.add_to(*fleet_);
  fleet_->footer(
      "A row is STALE when its last message is older than three periods of its slowest one.\n"
      "A process discovered whose status has not come by the end says \"still listening\".\n"
      "Exit: 0 something heard (--watch: stopped by SIGINT/SIGTERM), 2 usage, 3 nothing heard\n"
      "(what was listened for is printed).");
}

// One listing's wait: at least `window`; then until every process heard is described
// (FleetListener::settled), at most `bound`. The task manager is asked all along (a
// manager discovered late missed the first copies). False on SIGINT/SIGTERM.
bool FleetCommand::listen(FleetListener& listener, ManagerClient& manager, const Window& window) {
  const std::int64_t start_ns = clock::monotonic_ns();
  manager.start(manager_query());
  bool answered = false;
  while (true) {
    if (!answered) {
      if (const auto reply = manager.answer()) {
        listener.heard(*reply);
        answered = true;
      }
    }
    listener.note_discoveries(manager);
    const std::int64_t listened_ns = clock::monotonic_ns() - start_ns;
    if (listened_ns >= clock::s_to_ns(window.bound_s)) return true;
    if (listened_ns >= clock::s_to_ns(window.min_s) && listener.settled()) return true;
    if (process::ShutdownSignal::wait_for(kListenStep)) return false;
  }
}

// The first listing lasts one discovery period, the fleet's announcement period (config/
// dds.yaml, the same for every process), then waits for what it discovered late. A
// --watch listing after it hears a fleet already discovered: --listen-s, no more.
FleetCommand::Window FleetCommand::first_window(const dds::ParticipantOptions& options) const {
  const double announcement_s = options.announcement_period_s > 0.0 ? options.announcement_period_s
                                                                    : kFastDdsAnnouncementPeriod_s;
  const double min_s = std::max(listen_s_, announcement_s + kEndpointMatching_s);
  return {min_s, min_s + kDescribeWait_s};
}

bool FleetCommand::chosen() const {
  return fleet_->parsed();
}

int FleetCommand::run() {
  const dds::ParticipantOptions options = dds_.resolve("cover-fleet");
  dds::Participant participant(options);
  FleetListener listener(participant, size_, listen_s_);
  ManagerClient manager(participant, clock::to_milliseconds(listen_s_));
  const bool terminal = watch_ && !json_ && isatty(STDOUT_FILENO) != 0;
  bool heard_any = false;
  Window window = first_window(options);
  while (true) {
    const std::int64_t started_ns = clock::monotonic_ns();
    if (!listen(listener, manager, window)) {
      if (!watch_) return kFleetInterrupted;
      break;
    }
    const double listened_s = static_cast<double>(clock::monotonic_ns() - started_ns) / 1e9;
    window = {listen_s_, listen_s_};
    const std::vector<FleetRow> rows = listener.rows();
    heard_any = heard_any || !rows.empty();
    char listened[32];
    std::snprintf(listened, sizeof listened, "%.2f", listened_s);
    const std::string nothing =
        "nothing heard on DDS domain " + std::to_string(options.domain_id) + " within " + listened +
        " s; listened for " + listener.listened_for() + " and a task manager's answer on " +
        dds::topics::manager_reply().name() + " (is the fleet on this domain and network?)";
    if (json_) {
      nlohmann::ordered_json doc;
      doc["domain"] = options.domain_id;
      doc["vendor"] = dds::vendor_name(options.vendor);
      doc["listen_s"] = listen_s_;
      doc["listened_s"] = listened_s;
      doc["rows"] = fleet_json(rows);
      std::cout << doc.dump() << std::endl;
      if (rows.empty() && !watch_) std::cerr << "cover fleet: " << nothing << "\n";
    } else {
      if (terminal) {
        std::cout << "\033[H\033[2J"
                  << "cover fleet: DDS domain " << options.domain_id << ", every " << listen_s_
                  << " s (Ctrl-C stops)\n";
      }
      if (rows.empty()) {
        (watch_ ? std::cout : std::cerr) << (watch_ ? "" : "cover fleet: ") << nothing << "\n";
      } else {
        std::cout << fleet_table(rows);
      }
      if (watch_ && !terminal) std::cout << "\n";
      std::cout << std::flush;
    }
    if (!watch_) break;
  }
  return heard_any ? kFleetHeard : kFleetNothing;
}

}  // namespace cover::cli
