#pragma once

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <string>

#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"

namespace cover::cli {

// A ground station's line to the flight-controller bridges: one operator command out
// (cover/fc/request), the autopilot's answer back (cover/fc/reply, matched by request id).
class FcClient {
 public:
  FcClient(dds::Participant& participant, std::chrono::milliseconds timeout);
  // nullopt when no bridge answered within the timeout (none running for that UAV, or
  // not reachable on this network and domain).
  std::optional<msg::FcReply> call(std::uint32_t uav_id, msg::FcCommandKind kind);

 private:
  void on_reply(const msg::FcReply& reply);

  std::chrono::milliseconds timeout_;
  std::mutex mutex_;
  std::condition_variable arrived_;
  std::string awaited_id_;
  std::optional<msg::FcReply> reply_;
  dds::Writer<msg::FcRequest> writer_;
  dds::Reader<msg::FcReply> reader_;  // last: its callback uses the members above
};

}  // namespace cover::cli
