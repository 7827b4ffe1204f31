#include "fc_client.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <random>

#include "cover/clock/clock.hpp"
#include "manager_client.hpp"

namespace cover::cli {
namespace {
// A bridge answers once its autopilot has (its COMMAND_ACK, or its own retries ran out):
// the request is sent again meanwhile only for a bridge that matched late, and a bridge
// answers a repeated id with its first answer.
constexpr std::chrono::milliseconds kResendPeriod{300};
}  // namespace

FcClient::FcClient(dds::Participant& participant, std::chrono::milliseconds timeout)
    : timeout_(timeout),
      writer_(participant.make_writer(dds::topics::fc_request())),
      reader_(participant.make_reader(dds::topics::fc_reply(),
                                      [this](const msg::FcReply& r) { on_reply(r); })) {}

void FcClient::on_reply(const msg::FcReply& reply) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (reply.request_id != awaited_id_) return;  // another station's
    reply_ = reply;
  }
  arrived_.notify_all();
}

std::optional<msg::FcReply> FcClient::call(std::uint32_t uav_id, msg::FcCommandKind kind) {
  const auto deadline = std::chrono::steady_clock::now() + timeout_;
  auto left = [&] {
    return std::chrono::duration_cast<std::chrono::milliseconds>(deadline -
                                                                 std::chrono::steady_clock::now());
  };
  if (!writer_.wait_for_readers(1, timeout_) || !reader_.wait_for_writers(1, left())) {
    return std::nullopt;
  }
  static const std::uint64_t salt = std::random_device{}();
  // Distinct per call: the ground station sends many commands from one process.
  static std::atomic<std::uint64_t> counter{0};
  msg::FcRequest request;
  request.submitter = ManagerClient::submitter();
  request.request_id = request.submitter + "/" + std::to_string(getpid()) + "/fc/" +
                       std::to_string(salt % 100000) + "/" + std::to_string(++counter);
  request.uav_id = uav_id;
  request.kind = kind;
  request.stamp_ns = clock::system_ns();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    awaited_id_ = request.request_id;
    reply_.reset();
  }
  std::unique_lock<std::mutex> lock(mutex_);
  while (std::chrono::steady_clock::now() < deadline) {
    lock.unlock();
    writer_.write(request);
    lock.lock();
    const auto next = std::min(deadline, std::chrono::steady_clock::now() + kResendPeriod);
    if (arrived_.wait_until(lock, next, [this] { return reply_.has_value(); })) return reply_;
  }
  return std::nullopt;
}

}  // namespace cover::cli
