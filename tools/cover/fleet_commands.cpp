#include "fleet_commands.hpp"

#include <unistd.h>

#include <CLI/CLI.hpp>

#include <chrono>
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
#include "fleet_view.hpp"
#include "manager_client.hpp"

namespace cover::cli {
namespace {

// How often a listing looks whether a new row extends it.
constexpr std::chrono::milliseconds kListenStep{50};

}  // namespace

// Every reader `cover fleet` holds, feeding one FleetView. The readers are the last
// members: their callbacks use the view.
class FleetListener {
 public:
  FleetListener(dds::Participant& participant, const FleetSize& size, double listen_s)
      : participant_(participant), view_(listen_s) {
    for_each_fleet_topic_of<msg::UavStatus>(size, [&](const auto& t) { listen(t); });
    for_each_fleet_topic_of<msg::FcState>(size, [&](const auto& t) { listen(t); });
    for_each_fleet_topic_of<msg::UgvStatus>(size, [&](const auto& t) { listen(t); });
    listen(dds::topics::sim_clock());
    // The clock exchange names its askers and answerers ("host/process").
    peers_requests_ = participant.make_reader(
        dds::topics::time_request(),
        [this](const msg::TimeSyncRequest& r) { heard_peers({r.requester}); });
    peers_replies_ =
        participant.make_reader(dds::topics::time_reply(), [this](const msg::TimeSyncReply& r) {
          heard_peers({r.requester, r.responder});
        });
    listened_for_.insert(dds::topics::time_request().name());
    listened_for_.insert(dds::topics::time_reply().name());
  }

  void heard(const msg::ManagerReply& reply) {
    std::lock_guard<std::mutex> lock(mutex_);
    view_.heard(reply, dds::to_json(reply), clock::monotonic_ns());
  }
  std::int64_t newest_first_heard_ns() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return view_.newest_first_heard_ns();
  }
  std::vector<FleetRow> rows() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return view_.rows(clock::monotonic_ns());
  }
  // The topic patterns listened to, for the message when nothing was heard.
  std::string listened_for() const {
    std::string text;
    for (const std::string& t : listened_for_) text += (text.empty() ? "" : ", ") + t;
    return text;
  }

 private:
  template <typename T>
  void listen(const dds::Topic<T>& topic) {
    const dds::TopicInfo* info = dds::find_topic(topic.name());
    listened_for_.insert(info ? info->pattern : topic.name());
    std::get<std::vector<dds::Reader<T>>>(readers_).push_back(
        participant_.make_reader(topic, [this](const T& sample) {
          std::lock_guard<std::mutex> lock(mutex_);
          view_.heard(sample, dds::to_json(sample), clock::monotonic_ns());
        }));
  }
  void heard_peers(std::initializer_list<std::string> names) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const std::string& name : names) {
      if (!name.empty()) view_.heard_peer(name, clock::monotonic_ns());
    }
  }

  dds::Participant& participant_;
  mutable std::mutex mutex_;
  FleetView view_;
  std::set<std::string> listened_for_;
  std::tuple<std::vector<dds::Reader<msg::UavStatus>>, std::vector<dds::Reader<msg::FcState>>,
             std::vector<dds::Reader<msg::UgvStatus>>, std::vector<dds::Reader<msg::SimClock>>>
      readers_;
  dds::Reader<msg::TimeSyncRequest> peers_requests_;
  dds::Reader<msg::TimeSyncReply> peers_replies_;
};

namespace {

// Asks the task manager for its tasks not ended; a fleet without one is no error.
void query_manager(ManagerClient& client, FleetListener& listener) {
  msg::ManagerRequest request;
  request.kind = msg::ManagerRequestKind::MANAGER_QUERY;
  request.include_final = false;
  try {
    listener.heard(client.call(request));
  } catch (const ManagerUnreachable&) {
    // Absent from the listing, or "did not answer the query" when its clock requests came.
  }
}

}  // namespace

FleetCommand::FleetCommand(CLI::App& app) {
  fleet_ = app.add_subcommand(
      "fleet",
      "Every vehicle and process heard on the domain: kind, id, host/process, age, state, "
      "failsafe, task, autopilot");
  fleet_
      ->add_option("--listen-s", listen_s_,
                   "seconds to listen before listing (the slowest status, UGV agents' and the "
                   "clock exchange, comes once a second); a process first heard late is "
                   "listened to that long too, up to twice in all; --watch: the refresh period")
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
      "Exit: 0 something heard (--watch: stopped by SIGINT/SIGTERM), 2 usage, 3 nothing heard\n"
      "(what was listened for is printed).");
}

// One listing's wait: --listen-s, longer while rows keep appearing (each new one gets
// --listen-s, up to twice --listen-s in all). False on SIGINT/SIGTERM.
bool FleetCommand::listen(FleetListener& listener, ManagerClient& manager) const {
  const std::int64_t start_ns = clock::monotonic_ns();
  const std::int64_t window_ns = clock::s_to_ns(listen_s_);
  query_manager(manager, listener);
  while (true) {
    const std::int64_t end_ns =
        std::min(start_ns + 2 * window_ns,
                 std::max(start_ns + window_ns, listener.newest_first_heard_ns() + window_ns));
    const std::int64_t left_ns = end_ns - clock::monotonic_ns();
    if (left_ns <= 0) return true;
    const auto step = std::min(kListenStep, std::chrono::milliseconds(left_ns / 1'000'000 + 1));
    if (process::ShutdownSignal::wait_for(step)) return false;
  }
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
  while (true) {
    if (!listen(listener, manager)) {
      if (!watch_) return kFleetInterrupted;
      break;
    }
    const std::vector<FleetRow> rows = listener.rows();
    heard_any = heard_any || !rows.empty();
    const std::string nothing =
        "nothing heard on DDS domain " + std::to_string(options.domain_id) + " within " +
        std::to_string(listen_s_).substr(0, 4) + " s; listened for " + listener.listened_for() +
        " and a task manager's answer on " + dds::topics::manager_reply().name() +
        " (is the fleet on this domain and network?)";
    if (json_) {
      nlohmann::ordered_json doc;
      doc["domain"] = options.domain_id;
      doc["vendor"] = dds::vendor_name(options.vendor);
      doc["listen_s"] = listen_s_;
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
