#include "cover/time_sync/offset_monitor.hpp"

#include <spdlog/spdlog.h>

#include <chrono>

#include "cover/clock/clock.hpp"
#include "cover/time_sync/peer_name.hpp"

namespace cover::time_sync {

namespace {
// Requests a reply may still answer: a reply later than this many periods is useless
// (its delay would be seconds) and is refused with the unknown ones.
constexpr std::size_t kOutstanding = 64;
constexpr std::int64_t kSummaryPeriodNs = 60'000'000'000;
constexpr std::size_t kMaxNameBytes = 256;

std::string describe(const PeerOffset& p) {
  return fmt::format("{} {:+.3f} ms (+-{:.3f} ms, delay {:.3f} ms, {:.1f} s old)", p.peer,
                     ns_to_ms(p.estimate.offset_ns), ns_to_ms(p.estimate.uncertainty_ns),
                     ns_to_ms(p.estimate.delay_ns), static_cast<double>(p.estimate.age_ns) * 1e-9);
}
}  // namespace

OffsetMonitor::OffsetMonitor(dds::Participant& participant, MonitorOptions options)
    : options_(std::move(options)),
      name_(peer_name(options_.process)),
      burst_left_(options_.params.burst_count),
      peers_(static_cast<std::size_t>(options_.params.window_samples),
             clock::s_to_ns(options_.params.peer_timeout_s)),
      writer_(participant.make_writer(dds::topics::time_request())),
      reader_(participant.make_reader(dds::topics::time_reply(options_.process),
                                      [this](const msg::TimeSyncReply& r) { on_reply(r); })) {
  options_.params.validate();
  thread_ = std::thread([this] { run(); });
}

OffsetMonitor::~OffsetMonitor() {
  spdlog::info("clock replies delivered to {}: {} ({} for another asker), {} requests sent", name_,
               delivered_.load(), foreign_.load(), requests_sent());
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void OffsetMonitor::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stop_) {
    lock.unlock();
    send_request();
    log_changes(clock::system_ns());
    lock.lock();
    const bool burst = burst_left_ > 0;
    if (burst) --burst_left_;
    const double period_s =
        burst ? options_.params.burst_period_s : options_.params.request_period_s;
    // A peer appearing mid-period starts a burst: wake up for it.
    wake_.wait_for(lock, clock::to_milliseconds(period_s),
                   [&] { return stop_ || (!burst && burst_left_ > 0); });
  }
}

void OffsetMonitor::send_request() {
  msg::TimeSyncRequest request;
  request.requester = name_;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (options_.peers.empty() && options_.wait_for_peers) return;  // nobody to ask yet
    request.responders = options_.peers;
    ++sent_;
    request.request_id = next_request_id_++;
    request.t1_ns = clock::system_ns();
    outstanding_.emplace_back(request.request_id, request.t1_ns);
    while (outstanding_.size() > kOutstanding) outstanding_.pop_front();
  }
  writer_.write(request);
}

void OffsetMonitor::on_reply(const msg::TimeSyncReply& reply) {
  const std::int64_t t4_ns = clock::system_ns();
  ++delivered_;
  if (reply.requester != name_) {  // a namesake's on another host, or forged
    ++foreign_;
    return;
  }
  if (reply.responder.size() > kMaxNameBytes) return;
  std::lock_guard<std::mutex> lock(mutex_);
  // A reply to a request sent before set_peers dropped its responder.
  if (!peer_matches(reply.responder, options_.peers)) return;
  bool ours = false;
  for (const auto& [id, t1_ns] : outstanding_) {
    if (id == reply.request_id && t1_ns == reply.t1_ns) ours = true;
  }
  const auto sample = ours ? measure({reply.t1_ns, reply.t2_ns, reply.t3_ns, t4_ns})
                           : std::optional<OffsetSample>();
  if (!sample) {
    ++refused_;
    return;
  }
  if (!peers_.add(reply.responder, reply.responder_session, *sample)) start_burst_locked();
}

void OffsetMonitor::start_burst_locked() {
  burst_left_ = options_.params.burst_count;
  wake_.notify_all();
}

void OffsetMonitor::set_peers(std::vector<std::string> peers) {
  std::vector<std::string> gone;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (peers == options_.peers) return;
    options_.peers = std::move(peers);
    gone = peers_.forget_unless(
        [this](const std::string& peer) { return peer_matches(peer, options_.peers); });
    start_burst_locked();
  }
  for (const std::string& peer : gone) spdlog::info("clock of {} no longer asked", peer);
}

void OffsetMonitor::add_peer(const std::string& process) {
  std::lock_guard<std::mutex> lock(mutex_);
  for (const std::string& p : options_.peers) {
    if (p == process) return;
  }
  options_.peers.push_back(process);
  start_burst_locked();
}

std::vector<std::string> OffsetMonitor::peers() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return options_.peers;
}

std::uint64_t OffsetMonitor::requests_sent() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return sent_;
}

void OffsetMonitor::log_changes(std::int64_t now_ns) {
  std::vector<std::string> gone;
  std::vector<PeerOffset> all;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    gone = peers_.forget_silent(now_ns);
    all = peers_.all(now_ns);
  }
  for (const std::string& peer : gone) {
    spdlog::warn("clock of {} forgotten: no answer for {:.1f} s", peer,
                 options_.params.peer_timeout_s);
    logged_over_.erase(peer);
  }
  for (const PeerOffset& p : all) {
    const bool over = offset_limit_reason(name_, p, options_.params.max_offset_ms).has_value();
    const auto logged = logged_over_.find(p.peer);
    if (logged == logged_over_.end()) {
      if (over) {
        spdlog::warn("clock offset to {}: beyond the {:g} ms limit", describe(p),
                     options_.params.max_offset_ms);
      } else {
        spdlog::info("clock offset to {}", describe(p));
      }
    } else if (logged->second != over) {
      if (over) {
        spdlog::warn("clock offset to {}: now beyond the {:g} ms limit", describe(p),
                     options_.params.max_offset_ms);
      } else {
        spdlog::info("clock offset to {}: back within the {:g} ms limit", describe(p),
                     options_.params.max_offset_ms);
      }
    }
    logged_over_[p.peer] = over;
  }
  if (!all.empty() && now_ns >= next_summary_ns_) {
    if (next_summary_ns_ != 0) {
      std::string line;
      for (const PeerOffset& p : all) line += (line.empty() ? "" : "; ") + describe(p);
      spdlog::info("clock offsets: {}", line);
    }
    next_summary_ns_ = now_ns + kSummaryPeriodNs;
  }
}

std::vector<PeerOffset> OffsetMonitor::offsets() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return peers_.all(clock::system_ns());
}

std::optional<PeerOffset> OffsetMonitor::largest() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return peers_.largest(clock::system_ns());
}

std::optional<std::string> OffsetMonitor::limit_reason() const {
  const auto worst = largest();
  if (!worst) return std::nullopt;
  return offset_limit_reason(name_, *worst, options_.params.max_offset_ms);
}

std::uint64_t OffsetMonitor::refused_replies() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return refused_;
}

}  // namespace cover::time_sync
