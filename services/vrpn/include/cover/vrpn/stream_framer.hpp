#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "cover/vrpn/protocol.hpp"

namespace cover::vrpn {

// One message as it came off the stream; `payload` points into the framer's buffer and is
// valid only during the callback.
struct RawMessage {
  ServerTime time;
  std::int32_t sender = 0;
  std::int32_t type = 0;
  const std::uint8_t* payload = nullptr;
  std::size_t payload_bytes = 0;  // without the padding
};

using MessageHandler = std::function<void(const RawMessage&)>;

// Cuts a TCP byte stream (after the cookie) into messages. A length below the header's or
// above `max_message_bytes` means the stream is out of step (VRPN has no sync marker):
// the framer then stops delivering until reset(), and the connection must be dropped.
// The buffer is sized once; feeding allocates nothing.
class StreamFramer {
 public:
  explicit StreamFramer(std::size_t max_message_bytes);

  // Returns false once the stream is out of step (now or before).
  bool feed(const std::uint8_t* data, std::size_t size, const MessageHandler& on_message);
  void reset();

  bool desynchronised() const { return desynchronised_; }
  std::uint64_t messages() const { return messages_; }
  std::size_t pending_bytes() const { return have_; }
  // The bad length that put the stream out of step (valid once desynchronised()).
  std::int64_t bad_length() const { return bad_length_; }

 private:
  std::size_t max_message_bytes_;
  std::vector<std::uint8_t> buffer_;
  std::size_t have_ = 0;
  std::size_t need_ = kHeaderBytes;  // bytes of the current message (header, then all)
  bool desynchronised_ = false;
  std::int64_t bad_length_ = 0;
  std::uint64_t messages_ = 0;
};

}  // namespace cover::vrpn
