#include "manager_client.hpp"

#include <unistd.h>

#include <algorithm>

#include <atomic>
#include <cstdlib>
#include <random>

#include "cover/clock/clock.hpp"

namespace cover::cli {
namespace {
constexpr std::chrono::milliseconds kResendPeriod{300};
// Once the manager holds the request: re-sent only so that a manager restarted meanwhile
// gets it again (a repeat is answered, never carried out twice).
constexpr std::chrono::milliseconds kHeldResendPeriod{1000};

std::string seconds_text(std::chrono::milliseconds duration) {
  return std::to_string(std::chrono::duration<double>(duration).count()).substr(0, 4);
}
}  // namespace

ManagerClient::ManagerClient(dds::Participant& participant, std::chrono::milliseconds timeout,
                             std::chrono::milliseconds decision_timeout)
    : participant_(participant),
      timeout_(timeout),
      decision_timeout_(decision_timeout),
      writer_(participant.make_writer(dds::topics::manager_request())),
      reader_(participant.make_reader(dds::topics::manager_reply(),
                                      [this](const msg::ManagerReply& r) { on_reply(r); })) {}

void ManagerClient::on_reply(const msg::ManagerReply& reply) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (reply.request_id != awaited_id_) return;  // another station's
    if (!reply.interim) {
      reply_ = reply;
    } else if (!reply_) {
      interim_ = reply;
    }
  }
  arrived_.notify_all();
}

std::string ManagerClient::submitter() {
  char host[256] = "host";
  gethostname(host, sizeof host - 1);
  const char* user = std::getenv("USER");
  return std::string(user ? user : "user") + "@" + host;
}

std::string ManagerClient::next_request_id() {
  static const std::uint64_t salt = std::random_device{}();
  // One count for the process: two clients in one process (cover-ground-station's query
  // and command lines) must not give two requests the same id and take each other's replies.
  static std::atomic<std::uint64_t> counter{0};
  return submitter() + "/" + std::to_string(getpid()) + "/" + std::to_string(salt % 100000) + "/" +
         std::to_string(++counter);
}

void ManagerClient::address(msg::ManagerRequest& request) {
  request.request_id = next_request_id();
  request.submitter = submitter();
  request.stamp_ns = clock::system_ns();
  std::lock_guard<std::mutex> lock(mutex_);
  awaited_id_ = request.request_id;
  reply_.reset();
  interim_.reset();
}

void ManagerClient::start(msg::ManagerRequest request) {
  address(request);
  started_ = std::move(request);
  next_send_ = std::chrono::steady_clock::now();
}

std::optional<msg::ManagerReply> ManagerClient::answer() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (reply_) return reply_;
  }
  const auto now = std::chrono::steady_clock::now();
  if (started_ && now >= next_send_) {
    writer_.write(*started_);
    next_send_ = now + kResendPeriod;
  }
  return std::nullopt;
}

bool ManagerClient::wait_for_answer(std::unique_lock<std::mutex>& lock,
                                    std::chrono::steady_clock::time_point until) {
  return arrived_.wait_until(lock, until,
                             [this] { return reply_.has_value() || interim_.has_value(); });
}

msg::ManagerReply ManagerClient::call(msg::ManagerRequest request,
                                      const InterimHandler& on_interim) {
  using Clock = std::chrono::steady_clock;
  auto deadline = Clock::now() + timeout_;
  auto left = [&] {
    return std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
  };
  if (!writer_.wait_for_readers(1, timeout_) || !reader_.wait_for_writers(1, left())) {
    throw ManagerUnreachable("no task manager reachable within " + seconds_text(timeout_) +
                             " s (is cover-task-manager running on this DDS domain?)");
  }
  address(request);
  // Sent again until answered: a manager whose reader matched this writer a moment after
  // the writer matched it misses the first copy (volatile). The manager answers a repeated
  // request id with its first reply, so a request is carried out once.
  bool held = false;
  std::string held_for;  // the last interim message reported
  std::unique_lock<std::mutex> lock(mutex_);
  auto next_send = Clock::now();
  while (Clock::now() < deadline) {
    if (Clock::now() >= next_send) {
      lock.unlock();
      writer_.write(request);
      lock.lock();
      next_send = Clock::now() + (held ? kHeldResendPeriod : kResendPeriod);
    }
    if (!wait_for_answer(lock, std::min(deadline, next_send))) continue;
    if (reply_) return *reply_;
    const msg::ManagerReply interim = *interim_;
    interim_.reset();
    if (!held) deadline = std::max(deadline, Clock::now() + decision_timeout_);
    const bool news = !held || interim.message != held_for;
    held = true;
    held_for = interim.message;
    if (!news || !on_interim) continue;
    lock.unlock();
    on_interim(interim);
    lock.lock();
  }
  if (held) {
    throw ManagerUnreachable("the task manager held the request (" + held_for +
                             ") and did not decide it within " + seconds_text(decision_timeout_) +
                             " s");
  }
  throw ManagerUnreachable("the task manager did not answer within " + seconds_text(timeout_) +
                           " s");
}

}  // namespace cover::cli
