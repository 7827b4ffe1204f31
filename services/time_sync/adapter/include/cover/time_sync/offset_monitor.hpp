#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/time_sync/peer_offsets.hpp"
#include "cover/time_sync/time_sync_params.hpp"

namespace cover::time_sync {

struct MonitorOptions {
  std::string process;  // this process's name: it asks as "host/process"
  // The peers whose samples it takes, by process name ("cover-sim", "cover-ugv-agent-3",
  // "cover-ugv-agent-*" a prefix): its requests name them, and only they answer. Empty:
  // every peer (unless wait_for_peers).
  std::vector<std::string> peers;
  TimeSyncParams params;
  // Empty `peers` asks nobody (not everyone) until set_peers / add_peer names someone:
  // for a process that learns its peers from who asks it (a UGV agent).
  bool wait_for_peers = false;
};

// Estimates this host's clock offset to each peer it takes samples from: a request on
// cover/time/request every request_period_s (a burst at start and when a peer appears or
// restarts) addressed to those peers only (a fleet of P processes costs each responder
// the requests of its own askers, not P), the replies on this process's own topic
// cover/time/reply/<process> (so no asker receives another's; MonitorOptions::process must
// be a dds::valid_process_name), each reply turned into an OffsetSample, each peer's
// samples through NTP's clock filter. Logs each peer's first estimate, every crossing of
// max_offset_ms and a summary once a minute. Its own thread sends; the replies arrive on DDS's.
class OffsetMonitor {
 public:
  OffsetMonitor(dds::Participant& participant, MonitorOptions options);
  ~OffsetMonitor();
  OffsetMonitor(const OffsetMonitor&) = delete;
  OffsetMonitor& operator=(const OffsetMonitor&) = delete;

  const std::string& name() const { return name_; }
  double max_offset_ms() const { return options_.params.max_offset_ms; }
  std::vector<PeerOffset> offsets() const;
  std::optional<PeerOffset> largest() const;
  // Why a task must not start: the largest offset when it exceeds max_offset_ms.
  std::optional<std::string> limit_reason() const;
  std::uint64_t refused_replies() const;  // not matching a request of ours
  std::uint64_t requests_sent() const;
  // Replies DDS delivered to this monitor, and those of them for another asker (on its own
  // topic cover/time/reply/<process>, only a namesake's on another host or a forgery).
  std::uint64_t replies_delivered() const { return delivered_.load(); }
  std::uint64_t foreign_replies() const { return foreign_.load(); }

  // The peers asked from now on (MonitorOptions::peers); a peer no longer named is
  // forgotten at once, a newly named one is asked in a burst.
  void set_peers(std::vector<std::string> peers);
  // Adds one process name to the peers asked (nothing when it is named already).
  void add_peer(const std::string& process);
  std::vector<std::string> peers() const;

 private:
  void run();
  void send_request();
  void on_reply(const msg::TimeSyncReply& reply);
  void log_changes(std::int64_t now_ns);  // run()'s thread only
  void start_burst_locked();

  MonitorOptions options_;
  std::string name_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  int burst_left_ = 0;
  std::uint64_t next_request_id_ = 1;
  std::deque<std::pair<std::uint64_t, std::int64_t>> outstanding_;  // request id, t1
  PeerOffsets peers_;
  std::uint64_t refused_ = 0;
  std::uint64_t sent_ = 0;
  std::atomic<std::uint64_t> delivered_{0};
  std::atomic<std::uint64_t> foreign_{0};
  std::map<std::string, bool> logged_over_;  // peer -> beyond the limit when last logged
  std::int64_t next_summary_ns_ = 0;
  dds::Writer<msg::TimeSyncRequest> writer_;
  dds::Reader<msg::TimeSyncReply> reader_;  // after the members its callback uses
  std::thread thread_;                      // last: runs on everything above
};

}  // namespace cover::time_sync
