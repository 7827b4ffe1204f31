#include "cover/time_sync/clock_responder.hpp"

#include <spdlog/spdlog.h>

#include <chrono>
#include <optional>
#include <random>
#include <utility>

#include "cover/clock/clock.hpp"
#include "cover/time_sync/peer_name.hpp"

namespace cover::time_sync {

namespace {
// Peer names are host/process: longer is not a COVER process (and not logged verbatim).
constexpr std::size_t kMaxNameBytes = 256;
constexpr std::size_t kMaxAskers = 256;  // a fleet's processes, with room
// How long a new asker's writer waits for the asker's reader before the request that made it
// is answered (discovery on one host: tens of ms).
constexpr std::chrono::milliseconds kFirstReplyMatchWait{1000};
// How often the writers waiting for their askers' readers are looked at.
constexpr std::chrono::milliseconds kMatchPoll{5};

// The process part of "host/process" (all of it without a '/').
std::string process_of(const std::string& peer) {
  return peer.substr(peer.rfind('/') + 1);
}

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
    : participant_(participant),
      name_(peer_name(process)),
      session_(new_session()),
      on_new_asker_(std::move(on_new_asker)) {
  const std::int64_t offset_ns = clock::test_clock_offset_ns();
  if (offset_ns != 0) {
    spdlog::warn("answering clock requests as {} with a TEST clock offset of {:+.3f} ms", name_,
                 static_cast<double>(offset_ns) * 1e-6);
  } else {
    spdlog::info("answering clock requests (cover/time/request) as {}", name_);
  }
  thread_ = std::thread([this] { open_writers(); });
  reader_ = participant.make_reader(dds::topics::time_request(),
                                    [this](const msg::TimeSyncRequest& r) { on_request(r); });
}

ClockResponder::~ClockResponder() {
  reader_ = {};  // no request arrives from here on
  std::size_t askers = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    askers = writers_.size();
  }
  spdlog::info(
      "clock requests answered by {}: {} ({} for others, {} before the asker's "
      "writer, {} refused), to {} askers",
      name_, answered_.load(), not_addressed_.load(), unanswered_.load(), refused_.load(), askers);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void ClockResponder::open_writers() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    const auto work = [&] { return stop_ || !opening_.empty(); };
    if (matching_.empty()) {
      wake_.wait(lock, work);
    } else {
      wake_.wait_for(lock, kMatchPoll, work);
    }
    if (stop_) return;
    if (!opening_.empty()) open_writer(lock);
    answer_matched();
  }
}

void ClockResponder::open_writer(std::unique_lock<std::mutex>& lock) {
  const std::string asker = *opening_.begin();
  lock.unlock();
  std::optional<dds::Writer<msg::TimeSyncReply>> writer;
  try {
    writer.emplace(participant_.make_writer(dds::topics::time_reply(asker)));
  } catch (const std::exception& e) {
    spdlog::warn("cannot answer {}: {}", asker, e.what());
  }
  lock.lock();
  opening_.erase(asker);
  if (!writer) return;
  // From here on requests are answered as they come (map nodes stay where they are); the
  // one that made the writer waits for the asker's reader: written before it matched, a
  // reply would be lost (volatile).
  writers_.emplace(asker, std::move(*writer));
  matching_[asker] = Clock::now() + kFirstReplyMatchWait;
}

// The last request of an asker that came before its writer, answered late: t2 is when it
// arrived and t3 now, so the asker's offset stays right (the wait is not in its delay). A
// one-shot asker (`cover fleet`) would otherwise hear no one that met it after its first
// request.
void ClockResponder::answer_matched() {
  const auto now = Clock::now();
  for (auto it = matching_.begin(); it != matching_.end();) {
    dds::Writer<msg::TimeSyncReply>& writer = writers_.at(it->first);
    if (writer.matched_readers() == 0 && now < it->second) {
      ++it;
      continue;
    }
    const auto pending = pending_.find(it->first);
    if (pending != pending_.end()) {
      reply_now(writer, pending->second);
      pending_.erase(pending);
    }
    it = matching_.erase(it);
  }
}

void ClockResponder::reply_now(dds::Writer<msg::TimeSyncReply>& writer, msg::TimeSyncReply& reply) {
  reply.t3_ns = clock::system_ns();
  if (writer.write(reply)) ++answered_;
}

void ClockResponder::on_request(const msg::TimeSyncRequest& request) {
  const std::int64_t t2_ns = clock::system_ns();
  if (request.requester == name_) return;  // this process's own monitor asks the others
  const std::string asker = process_of(request.requester);
  if (request.requester.size() > kMaxNameBytes || !dds::valid_process_name(asker)) {
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
    const bool known = writers_.count(asker) != 0 || opening_.count(asker) != 0;
    if (!known && writers_.size() + opening_.size() >= kMaxAskers) {
      ++refused_;
      return;
    }
    new_asker = askers_.size() < kMaxAskers && askers_.insert(request.requester).second;
    const auto writer = writers_.find(asker);
    if (writer == writers_.end()) {
      ++unanswered_;
      pending_[asker] = reply;
      if (opening_.insert(asker).second) wake_.notify_all();
    } else {
      reply_now(writer->second, reply);
    }
  }
  if (!new_asker) return;
  spdlog::info("{} asks this process's clock", request.requester);
  if (on_new_asker_) on_new_asker_(request.requester);
}

}  // namespace cover::time_sync
