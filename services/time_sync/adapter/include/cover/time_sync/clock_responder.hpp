#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <mutex>
#include <set>
#include <string>

#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"

namespace cover::time_sync {

// Answers clock requests (cover/time/request) with this host's system clock: the request's
// arrival (t2) and the reply's departure (t3). Every process whose samples another host
// takes runs one, so that the taker can measure the offset between their clocks. It
// answers only the requests that name it (or name no one): a request for other
// processes costs it a lookup, not a reply that every asker would receive.
class ClockResponder {
 public:
  // Called once per process that asks this one's clock, with its "host/process" name, on
  // DDS's thread: who takes this process's samples (a UGV agent asks their clocks back).
  using AskerCallback = std::function<void(const std::string& asker)>;

  // `process`: this process's name ("cover-ugv-agent-1"); it answers as "host/process".
  ClockResponder(dds::Participant& participant, const std::string& process,
                 AskerCallback on_new_asker = {});

  const std::string& name() const { return name_; }
  std::uint64_t answered() const { return answered_.load(); }
  std::uint64_t refused() const { return refused_.load(); }              // malformed requests
  std::uint64_t not_addressed() const { return not_addressed_.load(); }  // for others

 private:
  void on_request(const msg::TimeSyncRequest& request);

  std::string name_;
  std::uint64_t session_;
  std::atomic<std::uint64_t> answered_{0};
  std::atomic<std::uint64_t> refused_{0};
  std::atomic<std::uint64_t> not_addressed_{0};
  AskerCallback on_new_asker_;
  std::mutex mutex_;              // the writer and the askers logged
  std::set<std::string> askers_;  // each logged (and called back) once
  dds::Writer<msg::TimeSyncReply> writer_;
  dds::Reader<msg::TimeSyncRequest> reader_;  // last: its callback uses the members above
};

}  // namespace cover::time_sync
