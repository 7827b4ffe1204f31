#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

namespace cover::foxglove {

// A Foxglove WebSocket client that subscribes to every channel a server advertises and
// counts what arrives: the load a Foxglove window showing everything puts on the bridge
// (cover-bench record). Connects on its own thread, retrying until stop(), so it can be
// started before the server. Never throws after construction.
class SubscriberClient {
 public:
  struct Counts {
    std::uint64_t channels_advertised = 0;
    std::uint64_t messages = 0;  // messageData frames
    std::uint64_t bytes = 0;     // their payload bytes
    bool connected = false;
  };

  // `uri`: ws://HOST:PORT.
  explicit SubscriberClient(std::string uri);
  ~SubscriberClient();
  SubscriberClient(const SubscriberClient&) = delete;
  SubscriberClient& operator=(const SubscriberClient&) = delete;

  Counts counts() const;
  void stop();

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cover::foxglove
