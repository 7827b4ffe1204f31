#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "cover/dds/participant.hpp"
#include "cover/mcap/reader.hpp"

namespace cover::recording {

struct PlayOptions {
  std::string path;
  double rate = 1.0;                     // 2: twice as fast
  std::vector<std::string> topic_globs;  // empty: every recorded topic
  double start_s = 0.0;                  // skip the recording's first S seconds
  double delay_s = 0.5;  // between making the writers and the first sample: discovery
  // Replay into live UAV agents with the simulator's lockstep protocol instead of at the
  // recorded pace (lockstep_replay.cpp): tick after tick, the inputs the tick names (its
  // relative_stamp_ns, imu_stamp_ns) are published, then the tick, then the player waits
  // for every agent that answered it in the recording to answer it again. Recorded UAV
  // commands are not played (the agents make them).
  bool lockstep = false;
  double answer_timeout_s = 5.0;  // lockstep: then the sample goes out anyway (counted)
};

struct PlayStats {
  std::uint64_t published = 0;
  std::uint64_t undecodable = 0;            // payloads that are not their type's CDR
  std::uint64_t answers_awaited = 0;        // lockstep: recorded commands waited for
  std::uint64_t answers_missing = 0;        // lockstep: of those, not heard within the timeout
  std::vector<std::string> skipped_topics;  // not catalogued, or another type than recorded
  std::vector<mcap::ReadIssue> issues;      // damaged or cut file: what was readable played
  bool is_mcap = false;
  bool stopped = false;  // stop_requested() said so before the end
};

// Publishes a recording's samples again, each on its topic with its recorded type, at the
// pace of their log times (scaled by `rate`): the CDR decoded by the vendor's type support
// (CdrCodec) and written by an ordinary typed writer, so receivers cannot tell a replay
// from the live system except by the stamps, which are the recorded ones.
class Player {
 public:
  Player(dds::Participant& participant, PlayOptions options);
  ~Player();
  Player(const Player&) = delete;
  Player& operator=(const Player&) = delete;

  // Plays to the end of the file, or until stop_requested() (checked at least every 50 ms).
  PlayStats run(const std::function<bool()>& stop_requested);

  // One topic's typed writer, fed the recorded CDR.
  class Publisher {
   public:
    virtual ~Publisher() = default;
    // False when the bytes are not the topic type's CDR.
    virtual bool publish(const std::uint8_t* data, std::size_t size) = 0;
    // Reliable topics: until the subscribers have every sample, at most `timeout`.
    virtual void wait_for_acknowledgments(std::chrono::milliseconds timeout) = 0;
  };

 private:
  bool prepare(PlayStats& stats);
  void listen_for_answers(const std::map<std::string, std::string>& recorded_types);
  // lockstep_replay.cpp
  PlayStats run_lockstep(PlayStats stats, const std::function<bool()>& stop_requested);
  bool wait_for_answers(const std::set<std::string>& topics, std::int64_t stamp_ns,
                        PlayStats& stats, const std::function<bool()>& stop_requested);

  dds::Participant& participant_;
  PlayOptions options_;
  std::map<std::string, std::unique_ptr<Publisher>> publishers_;  // by topic
  std::map<std::string, dds::Reader<msg::UavCommand>> answers_;   // lockstep, by topic
  std::uint64_t first_log_ns_ = 0;
};

}  // namespace cover::recording
