#pragma once

#include <chrono>
#include <condition_variable>
#include <functional>
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
// ignored). The manager may answer a submission at once with an interim reply
// (ManagerReply.interim: what it waits for, e.g. a vehicle not heard yet), then decide it:
// call() passes each interim reply to its handler and waits for the final one.
class ManagerClient {
 public:
  using InterimHandler = std::function<void(const msg::ManagerReply&)>;

  // `timeout`: to reach a manager and get its first answer. `decision_timeout`: once an
  // interim answer came, the wait for the final one (the manager decides within its
  // restart_grace_s, 10 s by default).
  ManagerClient(dds::Participant& participant, std::chrono::milliseconds timeout,
                std::chrono::milliseconds decision_timeout = std::chrono::seconds(60));
  // The final reply. Calls `on_interim` with each interim reply whose message is new.
  // Throws ManagerUnreachable when no manager matched, none answered within the timeout,
  // or a held request was not decided within the decision timeout.
  msg::ManagerReply call(msg::ManagerRequest request, const InterimHandler& on_interim = {});

  // The same request and resends without the wait, for a caller that listens to other
  // topics meanwhile (cover fleet): start() sends `request` under a new id; each answer()
  // sends it again when a resend period has passed (a manager discovered later missed the
  // earlier copies) and returns the final reply once it came. The caller decides how long.
  void start(msg::ManagerRequest request);
  std::optional<msg::ManagerReply> answer();
  // A task manager's reply writer is matched: a manager is on the domain.
  bool manager_discovered() const { return reader_.matched_writers() > 0; }

  dds::Participant& participant() { return participant_; }
  // "user@host", recorded with a submission.
  static std::string submitter();

 private:
  std::string next_request_id();
  // Gives `request` a new id, its submitter and stamp, and awaits the answer to that id.
  void address(msg::ManagerRequest& request);

  void on_reply(const msg::ManagerReply& reply);

  // Waits (mutex_ held by `lock`) until the final reply or an unreported interim one
  // arrives, or `until`. True when there is something to look at.
  bool wait_for_answer(std::unique_lock<std::mutex>& lock,
                       std::chrono::steady_clock::time_point until);

  dds::Participant& participant_;
  std::chrono::milliseconds timeout_;
  std::chrono::milliseconds decision_timeout_;
  std::mutex mutex_;
  std::condition_variable arrived_;
  std::string awaited_id_;
  std::optional<msg::ManagerReply> reply_;      // the final one
  std::optional<msg::ManagerReply> interim_;    // the latest interim one not yet reported
  std::optional<msg::ManagerRequest> started_;  // start()'s request, re-sent by answer()
  std::chrono::steady_clock::time_point next_send_;
  dds::Writer<msg::ManagerRequest> writer_;
  dds::Reader<msg::ManagerReply> reader_;  // last: its callback uses the members above
};

}  // namespace cover::cli
