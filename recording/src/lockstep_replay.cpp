// Player::run_lockstep: a lockstep recording replayed into live UAV agents in the order
// the simulator's lockstep protocol fixed, whatever order the recorder received it in.
#include <algorithm>
#include <chrono>
#include <deque>
#include <limits>
#include <map>

#include "cover/dds/cdr_codec.hpp"
#include "cover/recording/player.hpp"

namespace cover::recording {
namespace {

using Clock = std::chrono::steady_clock;

struct Held {
  std::int64_t stamp_ns = 0;
  std::vector<std::uint8_t> bytes;
};

struct Tick {
  msg::SimClock clock;
  std::string topic;
  std::vector<std::uint8_t> bytes;
};

// What a tick releases of a topic: the inputs it names, everything else up to its time.
std::int64_t release_limit_ns(const std::string& type, const msg::SimClock& tick) {
  if (type == msg::RelativeState::kTypeName) return tick.relative_stamp_ns;
  if (type == msg::UgvImu::kTypeName) return tick.imu_stamp_ns;
  return tick.stamp_ns;
}

template <typename T>
bool decode(const mcap::MessageView& m, T& sample) {
  static const dds::CdrCodec codec(dds::type_support<T>());
  return codec.deserialize(m.data, m.size, &sample);
}

}  // namespace

bool Player::wait_for_answers(const std::set<std::string>& topics, std::int64_t stamp_ns,
                              PlayStats& stats, const std::function<bool()>& stop_requested) {
  const auto deadline =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(
                         std::chrono::duration<double>(options_.answer_timeout_s));
  for (const auto& topic : topics) {
    auto& live = answers_.at(topic);
    ++stats.answers_awaited;
    while (true) {
      const std::uint64_t seen = live.received_count();
      const auto latest = live.latest();
      if (latest && latest->sample.stamp_ns >= stamp_ns) break;
      if (stop_requested && stop_requested()) return false;
      if (Clock::now() >= deadline) {
        ++stats.answers_missing;
        break;
      }
      live.wait_for_sample(std::chrono::milliseconds(50), seen);
    }
  }
  return true;
}

PlayStats Player::run_lockstep(PlayStats stats, const std::function<bool()>& stop_requested) {
  std::map<std::string, std::deque<Held>> inputs;  // by topic, in stamp order
  std::map<std::string, std::string> types;
  std::vector<Tick> ticks;
  std::map<std::int64_t, std::set<std::string>> answered;  // tick stamp -> command topics
  mcap::Reader reader(options_.path);
  reader.scan([&](const mcap::MessageView& m) {
    const std::string& topic = m.channel->topic;
    const std::string type = m.schema != nullptr ? m.schema->name : "";
    if (answers_.count(topic) != 0) {
      msg::UavCommand command;
      if (decode(m, command)) answered[command.stamp_ns].insert(topic);
    } else if (publishers_.count(topic) != 0 && type == msg::SimClock::kTypeName) {
      Tick tick{{}, topic, {m.data, m.data + m.size}};
      if (decode(m, tick.clock)) ticks.push_back(std::move(tick));
    } else if (publishers_.count(topic) != 0) {
      types[topic] = type;
      inputs[topic].push_back(
          {static_cast<std::int64_t>(m.header.publish_time_ns), {m.data, m.data + m.size}});
    }
    return true;
  });
  for (auto& [topic, queue] : inputs) {
    std::stable_sort(queue.begin(), queue.end(),
                     [](const Held& a, const Held& b) { return a.stamp_ns < b.stamp_ns; });
  }
  // A tick the simulator published again (no answer yet) is played once.
  std::stable_sort(ticks.begin(), ticks.end(),
                   [](const Tick& a, const Tick& b) { return a.clock.tick < b.clock.tick; });
  ticks.erase(
      std::unique(ticks.begin(), ticks.end(),
                  [](const Tick& a, const Tick& b) { return a.clock.tick == b.clock.tick; }),
      ticks.end());

  auto publish = [&](const std::string& topic, const std::vector<std::uint8_t>& bytes) {
    if (publishers_.at(topic)->publish(bytes.data(), bytes.size())) {
      ++stats.published;
    } else {
      ++stats.undecodable;
    }
  };
  auto release = [&](const msg::SimClock* tick) {
    for (auto& [topic, queue] : inputs) {
      const std::int64_t limit =
          tick ? release_limit_ns(types[topic], *tick) : std::numeric_limits<std::int64_t>::max();
      while (!queue.empty() && queue.front().stamp_ns <= limit) {
        publish(topic, queue.front().bytes);
        queue.pop_front();
      }
    }
  };
  for (const auto& tick : ticks) {
    release(&tick.clock);
    publish(tick.topic, tick.bytes);
    const auto answers = answered.find(tick.clock.stamp_ns);
    if (answers != answered.end() &&
        !wait_for_answers(answers->second, tick.clock.stamp_ns, stats, stop_requested)) {
      stats.stopped = true;
      return stats;
    }
  }
  release(nullptr);
  return stats;
}

}  // namespace cover::recording
