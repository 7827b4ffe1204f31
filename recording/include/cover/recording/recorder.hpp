#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "cover/dds/participant.hpp"
#include "cover/mcap/writer.hpp"
#include "cover/recording/fleet_tap.hpp"

namespace cover::recording {

struct RecorderOptions {
  std::string path;                      // the MCAP file (created or truncated)
  std::vector<std::string> topic_globs;  // empty: every catalogued topic of the fleet
  FleetSize fleet;
  mcap::WriterOptions writer;
  // Keep-last depth of the recorder's readers (the catalogue's is 1 for most topics): a
  // burst that arrives while the recorder's receive thread is descheduled waits in the
  // reader instead of overwriting its predecessor.
  int history_depth = 64;
  // Received samples not yet written, in bytes: beyond it new samples are dropped
  // (counted) rather than the recorder's memory growing without bound.
  std::size_t max_pending_bytes = 64 * 1024 * 1024;
};

struct RecorderStats {
  std::uint64_t received = 0;
  std::uint64_t written = 0;
  std::uint64_t dropped = 0;        // queue full or not serializable
  std::uint64_t bytes_written = 0;  // the file's size so far
  std::uint64_t topics_heard = 0;   // channels in the file
  std::uint64_t topics_subscribed = 0;
};

// Records DDS samples into an MCAP file: a FleetTap reads the concrete catalogued topics
// the globs select, each subscribed when discovery reports its first writer (a
// dds::PublicationWatch, as `ros2 bag record -a`: no reader for a topic nobody publishes),
// each sample serialized to the CDR that crossed the wire (CdrCodec) on the vendor's
// receive thread and queued; pump() (one thread) subscribes the topics whose writers
// appeared and writes the queue: a channel (encoding cdr) and its type's schema (omgidl,
// the type's IDL text) on a topic's first sample, log time = receive time (system clock),
// publish time = the sample's stamp_ns. Never throws after construction; a topic whose
// reader cannot be made is logged and left out.
class Recorder {
 public:
  // Throws std::runtime_error when the file cannot be created, dds::DdsError when a
  // reader cannot be made.
  Recorder(dds::Participant& participant, RecorderOptions options);
  ~Recorder();
  Recorder(const Recorder&) = delete;
  Recorder& operator=(const Recorder&) = delete;

  // Subscribes the topics whose first writer appeared and writes what arrived, waiting up
  // to `wait_ms` for either; false once the file cannot be written (error() says why).
  bool pump(int wait_ms);
  // Keeps writing until no sample arrived for `quiet_ms` (the receive path, behind under
  // load, catches up with what the network buffered) or `max_ms` passed: call at a stop,
  // before close().
  bool drain(int quiet_ms, int max_ms);
  // Stops the readers, writes what is queued and the summary. Idempotent.
  bool close();
  RecorderStats stats() const;
  const std::string& error() const { return writer_.error(); }

 private:
  struct Pending {
    std::uint32_t topic_index;
    mcap::MessageHeader header;
    std::vector<std::uint8_t> bytes;
  };
  struct TopicSlot {
    std::string name;
    std::string type_name;
    std::uint16_t channel_id = 0;  // 0: no sample yet
    std::uint32_t sequence = 0;
  };
  void enqueue(TapSample&& sample);
  void on_publication(const dds::DiscoveredPublication& publication);
  void subscribe_appeared(const std::vector<std::string>& topics);
  std::uint16_t channel_for(TopicSlot& slot);

  RecorderOptions options_;
  mcap::Writer writer_;
  std::vector<TopicSlot> slots_;  // one per subscribed topic, by FleetTap topic index
  std::map<std::string, std::uint16_t> schema_ids_;
  std::unique_ptr<FleetTap> tap_;  // the readers (FleetTap): one per subscribed topic

  mutable std::mutex mutex_;
  std::condition_variable arrived_;
  std::vector<Pending> queue_;
  std::vector<std::string> appeared_;  // topics whose writer discovery reported, not yet handled
  std::size_t pending_bytes_ = 0;
  std::uint64_t received_ = 0;
  std::uint64_t dropped_ = 0;
  std::int64_t last_received_ns_ = 0;  // monotonic
  std::atomic<std::uint64_t> written_{0};
  std::atomic<std::uint64_t> channels_{0};
  std::atomic<std::uint64_t> file_bytes_{0};
  bool closed_ = false;
  dds::PublicationWatch watch_;  // last: its handler uses the members above
};

}  // namespace cover::recording
