#include "cover/recording/recorder.hpp"

#include <chrono>
#include <utility>

#include "cover/clock/clock.hpp"
#include "cover/logging/log.hpp"
#include "cover/msg/idl_schema.hpp"

namespace cover::recording {
namespace {

constexpr std::size_t kWakeBytes = 1024 * 1024;

}  // namespace

Recorder::Recorder(dds::Participant& participant, RecorderOptions options)
    : options_(std::move(options)), writer_(options_.path, options_.writer) {
  FleetTapOptions tap;
  tap.topic_globs = options_.topic_globs;
  tap.fleet = options_.fleet;
  tap.history_depth = options_.history_depth;
  tap.subscribe_all = false;
  tap_ = std::make_unique<FleetTap>(participant, tap,
                                    [this](TapSample&& sample) { enqueue(std::move(sample)); });
  watch_ = participant.watch_publications(
      [this](const dds::DiscoveredPublication& publication) { on_publication(publication); });
}

Recorder::~Recorder() {
  close();
}

void Recorder::enqueue(TapSample&& sample) {
  Pending pending{sample.topic_index, {}, std::move(sample.bytes)};
  pending.header.log_time_ns = static_cast<std::uint64_t>(sample.received_ns);
  pending.header.publish_time_ns = sample.publish_time_ns;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++received_;
    last_received_ns_ = clock::monotonic_ns();
    if (closed_ || pending.bytes.empty() ||
        pending_bytes_ + pending.bytes.size() > options_.max_pending_bytes) {
      ++dropped_;
      return;
    }
    pending_bytes_ += pending.bytes.size();
    queue_.push_back(std::move(pending));
    // pump() takes the queue in batches, every wait_ms: waking it for every sample would
    // cost a context switch per sample (half the recorder's CPU at 900 samples/s).
    if (pending_bytes_ < kWakeBytes) return;
  }
  arrived_.notify_one();
}

// On discovery's thread: only noted, pump() makes the reader (no reader may be made here).
void Recorder::on_publication(const dds::DiscoveredPublication& publication) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    appeared_.push_back(publication.topic_name);
  }
  arrived_.notify_one();
}

void Recorder::subscribe_appeared(const std::vector<std::string>& topics) {
  for (const std::string& topic : topics) {
    try {
      if (!tap_->subscribe(topic)) continue;  // subscribed already, or not selected
    } catch (const std::exception& e) {
      spdlog::error("not recording {}: {}", topic, e.what());
      continue;
    }
    const TapTopic& added = tap_->topics().back();
    slots_.push_back(TopicSlot{added.name, added.type_name});
    spdlog::info("recording {} ({}): its first writer appeared", added.name, added.type_name);
  }
}

std::uint16_t Recorder::channel_for(TopicSlot& slot) {
  if (slot.channel_id != 0) return slot.channel_id;
  auto schema = schema_ids_.find(slot.type_name);
  if (schema == schema_ids_.end()) {
    const auto id =
        writer_.add_schema(slot.type_name, "omgidl", std::string(msg::idl_schema(slot.type_name)));
    schema = schema_ids_.emplace(slot.type_name, id).first;
  }
  slot.channel_id = writer_.add_channel(schema->second, slot.name, "cdr");
  channels_ = channels_ + 1;
  return slot.channel_id;
}

bool Recorder::pump(int wait_ms) {
  std::vector<Pending> batch;
  std::vector<std::string> appeared;
  {
    std::unique_lock<std::mutex> lock(mutex_);
    arrived_.wait_for(lock, std::chrono::milliseconds(wait_ms),
                      [&] { return pending_bytes_ >= kWakeBytes || !appeared_.empty(); });
    batch.swap(queue_);
    appeared.swap(appeared_);
    pending_bytes_ = 0;
  }
  // After taking the batch: none of its samples is of a topic subscribed now.
  subscribe_appeared(appeared);
  bool ok = writer_.error().empty();
  for (auto& pending : batch) {
    TopicSlot& slot = slots_[pending.topic_index];
    pending.header.channel_id = channel_for(slot);
    pending.header.sequence = slot.sequence++;
    ok = writer_.write(pending.header, pending.bytes.data(), pending.bytes.size()) && ok;
    if (ok) ++written_;
  }
  ok = writer_.flush_due() && ok;
  file_bytes_ = writer_.bytes_written();
  return ok;
}

bool Recorder::drain(int quiet_ms, int max_ms) {
  const std::int64_t start_ns = clock::monotonic_ns();
  bool ok = true;
  while (ok && clock::monotonic_ns() - start_ns < max_ms * 1'000'000LL) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (clock::monotonic_ns() - last_received_ns_ >= quiet_ms * 1'000'000LL) break;
    }
    ok = pump(10);
  }
  return ok;
}

bool Recorder::close() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (closed_) return writer_.error().empty();
  }
  watch_.stop();  // no topic appears past this line
  tap_->stop();   // no callback runs past this line
  {
    std::lock_guard<std::mutex> lock(mutex_);
    appeared_.clear();  // a writer that appeared just now gets no reader at the close
  }
  pump(0);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    closed_ = true;
  }
  const bool ok = writer_.close();
  file_bytes_ = writer_.bytes_written();
  return ok;
}

RecorderStats Recorder::stats() const {
  RecorderStats stats;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stats.received = received_;
    stats.dropped = dropped_;
  }
  stats.written = written_;
  stats.bytes_written = file_bytes_;
  stats.topics_heard = channels_;
  stats.topics_subscribed = slots_.size();
  return stats;
}

}  // namespace cover::recording
