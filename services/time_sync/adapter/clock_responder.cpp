#include "cover/time_sync/clock_responder.hpp"

#include <spdlog/spdlog.h>

#include <random>
#include <utility>

#include "cover/clock/clock.hpp"
#include "cover/time_sync/peer_name.hpp"

namespace cover::time_sync {

namespace {
// Peer names are host/process: longer is not a COVER process (and not logged verbatim).
constexpr std::size_t kMaxNameBytes = 256;
constexpr std::size_t kMaxAskers = 256;  // a fleet's processes, with room

std::uint64_t new_session() {
  std::random_device random;
  const std::uint64_t high = random();
  const std::uint64_t session =
      (high << 32) ^ random() ^ static_cast<std::uint64_t>(clock::monotonic_ns());
  return session == 0 ? 1 : session;
}
}  // namespace

ClockResponder::ClockResponder(dds::Participant& participant, const std::string& process,
                               AskerCallback on_new_asker)
    : name_(peer_name(process)),
      session_(new_session()),
      on_new_asker_(std::move(on_new_asker)),
      writer_(participant.make_writer(dds::topics::time_reply())) {
  const std::int64_t offset_ns = clock::test_clock_offset_ns();
  if (offset_ns != 0) {
    spdlog::warn("answering clock requests as {} with a TEST clock offset of {:+.3f} ms", name_,
                 static_cast<double>(offset_ns) * 1e-6);
  } else {
    spdlog::info("answering clock requests (cover/time/request) as {}", name_);
  }
  reader_ = participant.make_reader(dds::topics::time_request(),
                                    [this](const msg::TimeSyncRequest& r) { on_request(r); });
}

void ClockResponder::on_request(const msg::TimeSyncRequest& request) {
  const std::int64_t t2_ns = clock::system_ns();
  if (request.requester == name_) return;  // this process's own monitor asks the others
  if (request.requester.empty() || request.requester.size() > kMaxNameBytes) {
    ++refused_;
    return;
  }
  if (!peer_matches(name_, request.responders)) {
    ++not_addressed_;
    return;
  }
  msg::TimeSyncReply reply;
  reply.requester = request.requester;
  reply.responder = name_;
  reply.responder_session = session_;
  reply.request_id = request.request_id;
  reply.t1_ns = request.t1_ns;
  reply.t2_ns = t2_ns;
  bool new_asker = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    new_asker = askers_.size() < kMaxAskers && askers_.insert(request.requester).second;
    reply.t3_ns = clock::system_ns();
    if (writer_.write(reply)) ++answered_;
  }
  if (!new_asker) return;
  spdlog::info("{} asks this process's clock", request.requester);
  if (on_new_asker_) on_new_asker_(request.requester);
}

}  // namespace cover::time_sync
