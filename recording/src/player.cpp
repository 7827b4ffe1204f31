#include "cover/recording/player.hpp"

#include <algorithm>
#include <chrono>
#include <thread>

#include "cover/dds/cdr_codec.hpp"
#include "cover/dds/dds_error.hpp"
#include "cover/dds/topics.hpp"
#include "cover/recording/fleet_topics.hpp"

namespace cover::recording {

namespace {

using Clock = std::chrono::steady_clock;

template <typename T>
class TypedPublisher : public Player::Publisher {
 public:
  TypedPublisher(dds::Participant& participant, const std::string& topic)
      : codec_(dds::type_support<T>()),
        reliable_(dds::catalogued_topic<T>(topic).qos().reliability == dds::Reliability::Reliable),
        writer_(participant.make_writer(dds::catalogued_topic<T>(topic))) {}
  bool publish(const std::uint8_t* data, std::size_t size) override {
    if (!codec_.deserialize(data, size, &sample_)) return false;
    writer_.write(sample_);
    return true;
  }
  void wait_for_acknowledgments(std::chrono::milliseconds timeout) override {
    if (reliable_) writer_.wait_for_acknowledgments(timeout);
  }

 private:
  dds::CdrCodec codec_;
  bool reliable_;
  dds::Writer<T> writer_;
  T sample_;
};

// Sleeps until `when`, waking every 50 ms to ask stop_requested(); false when stopped.
bool sleep_until(Clock::time_point when, const std::function<bool()>& stop_requested) {
  while (Clock::now() < when) {
    if (stop_requested && stop_requested()) return false;
    std::this_thread::sleep_for(
        std::min<Clock::duration>(when - Clock::now(), std::chrono::milliseconds(50)));
  }
  return !(stop_requested && stop_requested());
}

}  // namespace

Player::Player(dds::Participant& participant, PlayOptions options)
    : participant_(participant), options_(std::move(options)) {}

Player::~Player() = default;

// First pass: every channel of the file (a topic first heard mid-recording has its
// Channel record mid-file), so that every writer exists, and is discovered, before the
// first sample goes out.
bool Player::prepare(PlayStats& stats) {
  std::map<std::string, std::string> types;  // topic -> schema name
  std::map<std::string, std::string> unplayed;
  bool any = false;
  mcap::Reader reader(options_.path);
  reader.scan([&](const mcap::MessageView& m) {
    const std::string type = m.schema != nullptr ? m.schema->name : "";
    const bool answer = options_.lockstep && type == msg::UavCommand::kTypeName;
    if (answer || !topic_selected(m.channel->topic, options_.topic_globs)) {
      unplayed.emplace(m.channel->topic, type);
      return true;
    }
    types.emplace(m.channel->topic, type);
    first_log_ns_ = any ? std::min(first_log_ns_, m.header.log_time_ns) : m.header.log_time_ns;
    any = true;
    return true;
  });
  stats.is_mcap = reader.is_mcap();
  stats.issues = reader.issues();
  for (const auto& [topic, type] : types) {
    bool made = false;
    try {
      made = msg::with_type(type, [&](auto tag) {
        using T = typename decltype(tag)::type;
        publishers_[topic] = std::make_unique<TypedPublisher<T>>(participant_, topic);
      });
    } catch (const dds::DdsError&) {
      made = false;  // not catalogued, or catalogued with another type
    }
    if (!made) stats.skipped_topics.push_back(topic);
  }
  if (options_.lockstep) listen_for_answers(unplayed);
  return stats.is_mcap;
}

void Player::listen_for_answers(const std::map<std::string, std::string>& recorded_types) {
  for (const auto& [topic, type] : recorded_types) {
    if (type != msg::UavCommand::kTypeName) continue;
    try {
      answers_.emplace(topic,
                       participant_.make_reader(dds::catalogued_topic<msg::UavCommand>(topic)));
    } catch (const dds::DdsError&) {
      // not a catalogued command topic: nothing to wait for
    }
  }
}

PlayStats Player::run(const std::function<bool()>& stop_requested) {
  PlayStats stats;
  if (!prepare(stats) || publishers_.empty()) return stats;
  if (!sleep_until(Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                      std::chrono::duration<double>(options_.delay_s)),
                   stop_requested)) {
    stats.stopped = true;
    return stats;
  }
  if (options_.lockstep) return run_lockstep(std::move(stats), stop_requested);
  const auto start_ns = first_log_ns_ + static_cast<std::uint64_t>(options_.start_s * 1e9);
  const double rate = options_.rate > 0 ? options_.rate : 1.0;
  const auto wall_start = Clock::now();
  mcap::Reader reader(options_.path);
  reader.scan([&](const mcap::MessageView& m) {
    if (m.header.log_time_ns < start_ns) return true;
    const auto publisher = publishers_.find(m.channel->topic);
    if (publisher == publishers_.end()) return true;
    const double offset_s = static_cast<double>(m.header.log_time_ns - start_ns) * 1e-9 / rate;
    const auto when = wall_start + std::chrono::duration_cast<Clock::duration>(
                                       std::chrono::duration<double>(offset_s));
    if (!sleep_until(when, stop_requested)) {
      stats.stopped = true;
      return false;
    }
    if (publisher->second->publish(m.data, m.size)) {
      ++stats.published;
    } else {
      ++stats.undecodable;
    }
    return true;
  });
  // The process ends after this: a reliable sample still on its way would be lost with
  // the writer (the last of 25 was, 3 of 3 runs here).
  for (auto& [topic, publisher] : publishers_) {
    publisher->wait_for_acknowledgments(std::chrono::seconds(2));
  }
  return stats;
}

}  // namespace cover::recording
