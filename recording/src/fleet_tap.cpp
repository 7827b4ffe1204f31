#include "cover/recording/fleet_tap.hpp"

#include <fnmatch.h>

#include <type_traits>
#include <utility>

#include "cover/clock/clock.hpp"
#include "cover/dds/cdr_codec.hpp"

namespace cover::recording {
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

}  // namespace

bool topic_selected(const std::string& topic, const std::vector<std::string>& globs) {
  if (globs.empty()) return true;
  for (const auto& glob : globs) {
    if (::fnmatch(glob.c_str(), topic.c_str(), 0) == 0) return true;
  }
  return false;
}

class FleetTap::Subscription {
 public:
  virtual ~Subscription() = default;
};

namespace {

template <typename T>
class TypedSubscription : public FleetTap::Subscription {
 public:
  std::shared_ptr<dds::CdrCodec> codec;
  dds::Reader<T> reader;  // last: destroyed first, with its receive thread
};

}  // namespace

template <typename T>
void FleetTap::add_reader(const dds::Topic<T>& topic) {
  static const auto codec = std::make_shared<dds::CdrCodec>(dds::type_support<T>());
  const auto index = static_cast<std::uint32_t>(topics_.size());
  auto subscription = std::make_unique<TypedSubscription<T>>();
  subscription->codec = codec;
  const auto deep = topic.with_history_depth(options_.history_depth)
                        .without_deadline()
                        .with_acknowledgement_delay(options_.acknowledgement_delay_s);
  subscription->reader = participant_.make_reader(deep, [this, index](const T& sample) {
    if (wanted_ && !wanted_(index)) return;
    TapSample tapped;
    tapped.topic_index = index;
    tapped.received_ns = clock::system_ns();
    tapped.publish_time_ns = publish_time_ns(sample, tapped.received_ns);
    if (!codec->serialize(sample, tapped.bytes)) tapped.bytes.clear();
    sink_(std::move(tapped));
  });
  // Listed once its reader exists: a reader that could not be made leaves no topic behind.
  topics_.push_back(TapTopic{topic.name(), T::kTypeName});
  subscriptions_.push_back(std::move(subscription));
}

FleetTap::FleetTap(dds::Participant& participant, const FleetTapOptions& options, Sink sink,
                   Wanted wanted)
    : participant_(participant),
      options_(options),
      sink_(std::move(sink)),
      wanted_(std::move(wanted)) {
  if (!options_.subscribe_all) return;
  for_each_fleet_topic(options_.fleet, [&](const auto& topic) {
    if (topic_selected(topic.name(), options_.topic_globs)) add_reader(topic);
  });
}

bool FleetTap::subscribe(const std::string& topic_name) {
  if (!topic_selected(topic_name, options_.topic_globs)) return false;
  for (const TapTopic& known : topics_) {
    if (known.name == topic_name) return false;
  }
  bool added = false;
  for_each_fleet_topic(options_.fleet, [&](const auto& topic) {
    if (added || topic.name() != topic_name) return;
    add_reader(topic);
    added = true;
  });
  return added;
}

FleetTap::~FleetTap() {
  stop();
}

void FleetTap::stop() {
  subscriptions_.clear();
}

}  // namespace cover::recording
