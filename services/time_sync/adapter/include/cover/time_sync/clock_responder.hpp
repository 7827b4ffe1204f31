#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <thread>

#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"

namespace cover::time_sync {

// Answers clock requests (cover/time/request) with this host's system clock: the request's
// arrival (t2) and the reply's departure (t3). Every process whose samples another host
// takes runs one, so that the taker can measure the offset between their clocks. It
// answers only the requests that name it (or name no one), each on its asker's own topic
// (cover/time/reply/<process>): a reply reaches its asker, not every asker of the fleet.
// The writer of an asker's topic is made on this object's thread when the asker's first
// request arrives (a vendor's receive thread must not make one); the last request that
// arrived before it exists is answered once the asker's reader matched it (<= 1 s). Askers
// wait for their match side by side: a fleet's askers arriving together are answered as
// soon as each one's reader matched, not one after the other.
class ClockResponder {
 public:
  // Called once per process that asks this one's clock, with its "host/process" name, on
  // DDS's thread: who takes this process's samples (a UGV agent asks their clocks back).
  using AskerCallback = std::function<void(const std::string& asker)>;

  // `process`: this process's name ("cover-ugv-agent-1"); it answers as "host/process".
  ClockResponder(dds::Participant& participant, const std::string& process,
                 AskerCallback on_new_asker = {});
  ~ClockResponder();
  ClockResponder(const ClockResponder&) = delete;
  ClockResponder& operator=(const ClockResponder&) = delete;

  const std::string& name() const { return name_; }
  std::uint64_t answered() const { return answered_.load(); }
  std::uint64_t refused() const { return refused_.load(); }              // malformed requests
  std::uint64_t not_addressed() const { return not_addressed_.load(); }  // for others
  // Addressed to this process but arrived before the asker's reply writer existed (the last
  // of them is answered when it does).
  std::uint64_t unanswered() const { return unanswered_.load(); }

 private:
  using Clock = std::chrono::steady_clock;

  void on_request(const msg::TimeSyncRequest& request);
  void open_writers();  // its thread: a writer for each asker queued by on_request
  // The first asker in opening_: its writer made (mutex_ unlocked meanwhile), then matching.
  void open_writer(std::unique_lock<std::mutex>& lock);
  // Answers the pending request of each matching asker whose reader matched or whose wait
  // is over. Called with mutex_ held.
  void answer_matched();
  // Stamps t3 and writes. Called with mutex_ held.
  void reply_now(dds::Writer<msg::TimeSyncReply>& writer, msg::TimeSyncReply& reply);

  dds::Participant& participant_;
  std::string name_;
  std::uint64_t session_;
  std::atomic<std::uint64_t> answered_{0};
  std::atomic<std::uint64_t> refused_{0};
  std::atomic<std::uint64_t> not_addressed_{0};
  std::atomic<std::uint64_t> unanswered_{0};
  AskerCallback on_new_asker_;
  std::mutex mutex_;  // everything below but the reader
  std::condition_variable wake_;
  bool stop_ = false;
  std::set<std::string> askers_;  // "host/process", each logged (and called back) once
  // By the asker's process name (its topic); an asker restarted on another host reuses it.
  std::map<std::string, dds::Writer<msg::TimeSyncReply>> writers_;
  std::set<std::string> opening_;  // asked for, its writer not made yet
  // Its writer made, its first reply held until the asker's reader matched or this deadline.
  std::map<std::string, Clock::time_point> matching_;
  std::map<std::string, msg::TimeSyncReply> pending_;  // by asker: its last request since
  std::thread thread_;
  dds::Reader<msg::TimeSyncRequest> reader_;  // last: its callback uses the members above
};

}  // namespace cover::time_sync
