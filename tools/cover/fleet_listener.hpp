#pragma once

#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "cover/clock/clock.hpp"
#include "cover/dds/json_codec.hpp"
#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/recording/fleet_topics.hpp"
#include "fleet_view.hpp"
#include "manager_client.hpp"

namespace cover::cli {

// The row kind of each status type.
inline FleetKind kind_of(const msg::UavStatus&) {
  return FleetKind::UavAgent;
}
inline FleetKind kind_of(const msg::FcState&) {
  return FleetKind::FcBridge;
}
inline FleetKind kind_of(const msg::UgvStatus&) {
  return FleetKind::UgvAgent;
}
inline FleetKind kind_of(const msg::SimClock&) {
  return FleetKind::Sim;
}

// Every reader `cover fleet` holds, feeding one FleetView. The readers are the last
// members: their callbacks use the view.
class FleetListener {
 public:
  // Called on the vendor's receive thread once a status sample is in the view, with the
  // row's kind, its id (none for the simulator) and the sample's own stamp_ns: keep it short.
  using StatusHook =
      std::function<void(FleetKind kind, std::optional<std::uint32_t> id, std::int64_t stamp_ns)>;

  FleetListener(dds::Participant& participant, const recording::FleetSize& size, double listen_s,
                StatusHook on_status = {})
      : participant_(participant),
        view_(listen_s),
        naming_grace_ns_(clock::s_to_ns(listen_s)),
        on_status_(std::move(on_status)) {
    recording::for_each_fleet_topic_of<msg::UavStatus>(size, [&](const auto& t) { listen(t); });
    recording::for_each_fleet_topic_of<msg::FcState>(size, [&](const auto& t) { listen(t); });
    recording::for_each_fleet_topic_of<msg::UgvStatus>(size, [&](const auto& t) { listen(t); });
    listen(dds::topics::sim_clock());
    // The clock exchange names its askers and answerers ("host/process"); the replies to
    // an asker are on its own topic: the fleet's askers' are read from the start, any
    // other asker's once its requests were heard (note_discoveries).
    for (const std::string& asker : dds::topics::clock_askers(size.uavs, size.ugvs)) {
      askers_.insert(asker);
    }
    follow_askers();
    peers_requests_ =
        participant.make_reader(dds::topics::time_request(), [this](const msg::TimeSyncRequest& r) {
          heard_peers({r.requester});
          std::lock_guard<std::mutex> lock(mutex_);
          const std::string asker = r.requester.substr(r.requester.rfind('/') + 1);
          if (askers_.size() < kMaxAskers && dds::valid_process_name(asker)) askers_.insert(asker);
        });
    listened_for_.insert(dds::topics::time_request().name());
    listened_for_.insert(dds::find_topic(dds::topics::time_reply("cover-sim").name())->pattern);
  }

  void heard(const msg::ManagerReply& reply) {
    std::lock_guard<std::mutex> lock(mutex_);
    view_.heard(reply, dds::to_json(reply), clock::monotonic_ns());
  }
  // Readers that matched a writer are rows from then on, heard or not; the task manager
  // too once its reply writer matched `manager`'s reader.
  // The matched counts are read before the view's lock is taken: a vendor holds its
  // reader's lock while it calls the reader's callback, which takes the view's.
  void note_discoveries(const ManagerClient& manager) {
    follow_askers();
    std::vector<const Matched*> found;
    for (const Matched& m : matched_) {
      if (m.writers()) found.push_back(&m);
    }
    const bool manager_found = manager.manager_discovered();
    const std::int64_t now_ns = clock::monotonic_ns();
    std::lock_guard<std::mutex> lock(mutex_);
    for (const Matched* m : found) view_.discovered(m->kind, m->id, now_ns);
    if (manager_found) view_.discovered(FleetKind::TaskManager, {}, now_ns);
  }
  // Every process heard is described (FleetView::settled).
  bool settled() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return view_.settled(clock::monotonic_ns(), naming_grace_ns_);
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
  // A reader of one status topic: its kind and id (the simulator's clock has none), and
  // whether a writer matched it.
  struct Matched {
    FleetKind kind;
    std::optional<std::uint32_t> id;
    std::function<bool()> writers;
  };

  // The readers of one type are made in id order (for_each_fleet_topic_of).
  template <typename T>
  void listen(const dds::Topic<T>& topic) {
    const dds::TopicInfo* info = dds::find_topic(topic.name());
    listened_for_.insert(info ? info->pattern : topic.name());
    auto& readers = std::get<std::vector<dds::Reader<T>>>(readers_);
    const auto id = static_cast<std::uint32_t>(readers.size());
    const FleetKind kind = kind_of(T{});
    const auto row_id = kind == FleetKind::Sim ? std::nullopt : std::optional(id);
    readers.push_back(participant_.make_reader(topic, [this, kind, row_id](const T& sample) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        view_.heard(sample, dds::to_json(sample), clock::monotonic_ns());
      }
      if (on_status_) on_status_(kind, row_id, sample.stamp_ns);
    }));
    matched_.push_back(
        {kind, row_id, [&readers, id] { return readers[id].matched_writers() > 0; }});
  }
  // A reader on the reply topic of each asker heard since the last call: its answerers
  // are heard there. Made here, not in the request's callback (a vendor's thread).
  void follow_askers() {
    std::vector<std::string> fresh;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      for (const std::string& asker : askers_) {
        if (peers_replies_.count(asker) == 0) fresh.push_back(asker);
      }
    }
    for (const std::string& asker : fresh) {
      peers_replies_.emplace(asker,
                             participant_.make_reader(dds::topics::time_reply(asker),
                                                      [this](const msg::TimeSyncReply& r) {
                                                        heard_peers({r.requester, r.responder});
                                                      }));
    }
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
  std::int64_t naming_grace_ns_;
  StatusHook on_status_;
  std::set<std::string> listened_for_;
  std::vector<Matched> matched_;
  std::tuple<std::vector<dds::Reader<msg::UavStatus>>, std::vector<dds::Reader<msg::FcState>>,
             std::vector<dds::Reader<msg::UgvStatus>>, std::vector<dds::Reader<msg::SimClock>>>
      readers_;
  static constexpr std::size_t kMaxAskers = 256;  // a fleet's processes, with room
  std::set<std::string> askers_;                  // process names heard asking
  dds::Reader<msg::TimeSyncRequest> peers_requests_;
  std::map<std::string, dds::Reader<msg::TimeSyncReply>> peers_replies_;  // by asker
};

}  // namespace cover::cli
