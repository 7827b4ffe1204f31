#include "recorder.hpp"

#include <fnmatch.h>

#include <chrono>
#include <type_traits>
#include <utility>

#include "cover/clock/clock.hpp"
#include "cover/dds/cdr_codec.hpp"
#include "cover/msg/idl_schema.hpp"

namespace cover::cli {
namespace {

template <typename T, typename = void>
struct HasStamp : std::false_type {};
template <typename T>
struct HasStamp<T, std::void_t<decltype(std::declval<T>().stamp_ns)>> : std::true_type {};

// The sample's own stamp (simulated time from 0 in a lockstep run); its receive time for
// a negative stamp or a type without one (none today).
template <typename T>
std::uint64_t publish_time_ns(const T& sample, std::int64_t received_ns) {
  if constexpr (HasStamp<T>::value) {
    return sample.stamp_ns >= 0 ? static_cast<std::uint64_t>(sample.stamp_ns)
                                : static_cast<std::uint64_t>(received_ns);
  } else {
    return static_cast<std::uint64_t>(received_ns);
  }
}

constexpr std::size_t kWakeBytes = 1024 * 1024;

}  // namespace

bool topic_selected(const std::string& topic, const std::vector<std::string>& globs) {
  if (globs.empty()) return true;
  for (const auto& glob : globs) {
    if (::fnmatch(glob.c_str(), topic.c_str(), 0) == 0) return true;
  }
  return false;
}

class Recorder::Subscription {
 public:
  virtual ~Subscription() = default;
};

namespace {

template <typename T>
class TypedSubscription : public Recorder::Subscription {
 public:
  std::shared_ptr<dds::CdrCodec> codec;
  dds::Reader<T> reader;  // last: destroyed first, with its receive thread
};

}  // namespace

template <typename T>
void Recorder::subscribe(dds::Participant& participant, const dds::Topic<T>& topic) {
  if (!topic_selected(topic.name(), options_.topic_globs)) return;
  static const auto codec = std::make_shared<dds::CdrCodec>(dds::type_support<T>());
  const auto index = static_cast<std::uint32_t>(slots_.size());
  slots_.push_back(TopicSlot{topic.name(), T::kTypeName});
  auto subscription = std::make_unique<TypedSubscription<T>>();
  subscription->codec = codec;
  const auto deep = topic.with_history_depth(options_.history_depth).without_deadline();
  subscription->reader = participant.make_reader(deep, [this, index](const T& sample) {
    const std::int64_t received_ns = clock::system_ns();
    Pending pending{index, {}, {}};
    pending.header.log_time_ns = static_cast<std::uint64_t>(received_ns);
    pending.header.publish_time_ns = publish_time_ns(sample, received_ns);
    if (!codec->serialize(sample, pending.bytes)) pending.bytes.clear();
    enqueue(std::move(pending));
  });
  subscriptions_.push_back(std::move(subscription));
}

Recorder::Recorder(dds::Participant& participant, RecorderOptions options)
    : options_(std::move(options)), writer_(options_.path, options_.writer) {
  for_each_fleet_topic(options_.fleet, [&](const auto& topic) { subscribe(participant, topic); });
}

Recorder::~Recorder() {
  close();
}

void Recorder::enqueue(Pending pending) {
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
  {
    std::unique_lock<std::mutex> lock(mutex_);
    arrived_.wait_for(lock, std::chrono::milliseconds(wait_ms),
                      [&] { return pending_bytes_ >= kWakeBytes; });
    batch.swap(queue_);
    pending_bytes_ = 0;
  }
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
  subscriptions_.clear();  // no callback runs past this line
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

}  // namespace cover::cli
