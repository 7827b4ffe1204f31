#include "manager_client.hpp"

#include <unistd.h>

#include <algorithm>

#include <cstdlib>
#include <random>

#include "cover/clock/clock.hpp"

namespace cover::cli {
namespace {
constexpr std::chrono::milliseconds kResendPeriod{300};
}  // namespace

ManagerClient::ManagerClient(dds::Participant& participant, std::chrono::milliseconds timeout)
    : participant_(participant),
      timeout_(timeout),
      writer_(participant.make_writer(dds::topics::manager_request())),
      reader_(participant.make_reader(dds::topics::manager_reply(),
                                      [this](const msg::ManagerReply& r) { on_reply(r); })) {}

void ManagerClient::on_reply(const msg::ManagerReply& reply) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (reply.request_id != awaited_id_) return;  // another station's
    reply_ = reply;
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
  return submitter() + "/" + std::to_string(getpid()) + "/" + std::to_string(salt % 100000) + "/" +
         std::to_string(++counter_);
}

msg::ManagerReply ManagerClient::call(msg::ManagerRequest request) {
  const auto deadline = std::chrono::steady_clock::now() + timeout_;
  const double timeout_s = std::chrono::duration<double>(timeout_).count();
  auto left = [&] {
    return std::chrono::duration_cast<std::chrono::milliseconds>(deadline -
                                                                 std::chrono::steady_clock::now());
  };
  if (!writer_.wait_for_readers(1, timeout_) || !reader_.wait_for_writers(1, left())) {
    throw ManagerUnreachable("no task manager reachable within " +
                             std::to_string(timeout_s).substr(0, 4) +
                             " s (is cover-task-manager running on this DDS domain?)");
  }
  request.request_id = next_request_id();
  request.submitter = submitter();
  request.stamp_ns = clock::system_ns();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    awaited_id_ = request.request_id;
    reply_.reset();
  }
  // Sent again until answered: a manager whose reader matched this writer a moment after
  // the writer matched it misses the first copy (volatile). The manager answers a repeated
  // request id with its first reply, so a request is carried out once.
  std::unique_lock<std::mutex> lock(mutex_);
  while (std::chrono::steady_clock::now() < deadline) {
    lock.unlock();
    writer_.write(request);
    lock.lock();
    const auto next = std::min(deadline, std::chrono::steady_clock::now() + kResendPeriod);
    if (arrived_.wait_until(lock, next, [this] { return reply_.has_value(); })) return *reply_;
  }
  throw ManagerUnreachable("the task manager did not answer within " +
                           std::to_string(timeout_s).substr(0, 4) + " s");
}

}  // namespace cover::cli
