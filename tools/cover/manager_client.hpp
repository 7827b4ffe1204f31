#pragma once

#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>

#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"

namespace cover::cli {

// No task manager answered: not running, or not reachable on this network and domain.
class ManagerUnreachable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A ground station's line to cover-task-manager: one request out (cover/manager/request),
// its reply back (cover/manager/reply, matched by request id; other stations' replies are
// ignored).
class ManagerClient {
 public:
  ManagerClient(dds::Participant& participant, std::chrono::milliseconds timeout);
  // Throws ManagerUnreachable when no manager matched or none replied within the timeout.
  msg::ManagerReply call(msg::ManagerRequest request);

  dds::Participant& participant() { return participant_; }
  // "user@host", recorded with a submission.
  static std::string submitter();

 private:
  std::string next_request_id();

  void on_reply(const msg::ManagerReply& reply);

  dds::Participant& participant_;
  std::chrono::milliseconds timeout_;
  std::uint64_t counter_ = 0;
  std::mutex mutex_;
  std::condition_variable arrived_;
  std::string awaited_id_;
  std::optional<msg::ManagerReply> reply_;
  dds::Writer<msg::ManagerRequest> writer_;
  dds::Reader<msg::ManagerReply> reader_;  // last: its callback uses the members above
};

}  // namespace cover::cli
