#pragma once

#include <atomic>
#include <cstdint>
#include <mutex>
#include <set>
#include <string>

#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"

namespace cover::time_sync {

// Answers clock requests (cover/time/request) with this host's system clock: the request's
// arrival (t2) and the reply's departure (t3). Every process whose samples another host
// takes runs one, so that the taker can measure the offset between their clocks.
class ClockResponder {
 public:
  // `process`: this process's name ("cover-ugv-agent-1"); it answers as "host/process".
  ClockResponder(dds::Participant& participant, const std::string& process);

  const std::string& name() const { return name_; }
  std::uint64_t answered() const { return answered_.load(); }
  std::uint64_t refused() const { return refused_.load(); }  // malformed requests

 private:
  void on_request(const msg::TimeSyncRequest& request);

  std::string name_;
  std::uint64_t session_;
  std::atomic<std::uint64_t> answered_{0};
  std::atomic<std::uint64_t> refused_{0};
  std::mutex mutex_;              // the writer and the askers logged
  std::set<std::string> askers_;  // each logged once
  dds::Writer<msg::TimeSyncReply> writer_;
  dds::Reader<msg::TimeSyncRequest> reader_;  // last: its callback uses the members above
};

}  // namespace cover::time_sync
