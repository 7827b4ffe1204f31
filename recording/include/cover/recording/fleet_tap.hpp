#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "cover/dds/participant.hpp"
#include "cover/recording/fleet_topics.hpp"

namespace cover::recording {

// One sample as it crossed the wire: the CDR bytes (with the 4-byte encapsulation header)
// that dds::CdrCodec makes from the received sample, and its times.
struct TapSample {
  std::uint32_t topic_index = 0;      // into FleetTap::topics()
  std::int64_t received_ns = 0;       // system clock at the receive callback
  std::uint64_t publish_time_ns = 0;  // the sample's stamp_ns (its receive time without one)
  std::vector<std::uint8_t> bytes;    // empty: the sample could not be serialized
};

struct TapTopic {
  std::string name;       // cover/uav/0/rel/1
  std::string type_name;  // cover::idl::RelativeState (the IDL schema's root)
};

struct FleetTapOptions {
  std::vector<std::string> topic_globs;  // empty: every catalogued topic of the fleet
  FleetSize fleet;
  // Keep-last depth of the readers (the catalogue's is 1 for most topics): a burst that
  // arrives while the receive thread is descheduled waits in the reader instead of
  // overwriting its predecessor.
  int history_depth = 64;
  // Reliable topics: one acknowledgement per writer per this delay instead of one per
  // heartbeat (Fast DDS: 5 ms, i.e. per sample of a 100 Hz reliable writer): the recorder's
  // second thread woke ~540 times a second for them in Scenario 2 (110 ms of CPU per 10 s,
  // 40 ms with 50 ms). Writers keep unacknowledged samples that long, within their history.
  double acknowledgement_delay_s = 0.05;
  // True: a reader for every selected topic at construction (the live view advertises them
  // all). False: none; the owner subscribes each topic with subscribe() when its first
  // writer appears (the recorder, as `ros2 bag record -a`: no reader for a topic nobody
  // publishes, which Fast DDS would check on every sample it receives).
  bool subscribe_all = true;
};

// A type-erased reader of the concrete catalogued topics a set of globs selects (the
// recorder's and the live bridge's input): each sample is serialized on the vendor's
// receive thread to the CDR that crossed the wire and handed to `sink`. `wanted(index)`,
// when given, is asked first: false skips the serialization (nobody listens to it now).
// The readers ask for no deadline (deadline is requested <= offered, so they still match
// every writer; Fast DDS reschedules a deadline timer on every sample).
class FleetTap {
 public:
  using Sink = std::function<void(TapSample&&)>;
  using Wanted = std::function<bool(std::uint32_t topic_index)>;

  // Throws dds::DdsError when a reader cannot be made.
  FleetTap(dds::Participant& participant, const FleetTapOptions& options, Sink sink,
           Wanted wanted = {});
  ~FleetTap();
  FleetTap(const FleetTap&) = delete;
  FleetTap& operator=(const FleetTap&) = delete;

  // The topics subscribed so far, in the order subscribed (with subscribe_all: every
  // selected one, in catalogue order, fixed after construction). A sample's topic_index
  // indexes it; indices stay valid as topics are added.
  const std::vector<TapTopic>& topics() const { return topics_; }
  // Subscribes `topic_name` when it is a concrete catalogued topic of the fleet that the
  // globs select and is not subscribed yet: true when it was subscribed now. Call from the
  // thread that reads topics(). Throws dds::DdsError when the reader cannot be made.
  bool subscribe(const std::string& topic_name);
  // Destroys the readers: no sink call runs past it. Idempotent.
  void stop();

  class Subscription;  // one topic's reader, type-erased

 private:
  template <typename T>
  void add_reader(const dds::Topic<T>& topic);

  dds::Participant& participant_;
  FleetTapOptions options_;
  Sink sink_;
  Wanted wanted_;
  std::vector<TapTopic> topics_;
  std::vector<std::unique_ptr<Subscription>> subscriptions_;
};

}  // namespace cover::recording
