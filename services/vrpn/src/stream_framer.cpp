#include "cover/vrpn/stream_framer.hpp"

#include <algorithm>
#include <cstring>

#include "big_endian.hpp"

namespace cover::vrpn {

StreamFramer::StreamFramer(std::size_t max_message_bytes)
    : max_message_bytes_(std::max(max_message_bytes, kHeaderBytes)),
      buffer_(ceil8(std::max(max_message_bytes, kHeaderBytes))) {}

void StreamFramer::reset() {
  have_ = 0;
  need_ = kHeaderBytes;
  desynchronised_ = false;
  bad_length_ = 0;
}

bool StreamFramer::feed(const std::uint8_t* data, std::size_t size,
                        const MessageHandler& on_message) {
  while (size > 0 && !desynchronised_) {
    const std::size_t take = std::min(size, need_ - have_);
    std::memcpy(buffer_.data() + have_, data, take);
    have_ += take;
    data += take;
    size -= take;
    if (have_ < need_) break;
    const std::int64_t length = detail::load_i32(buffer_.data());
    if (need_ == kHeaderBytes) {
      // The length counts the header and the payload, not the payload's padding.
      if (length < static_cast<std::int64_t>(kHeaderBytes) ||
          length > static_cast<std::int64_t>(max_message_bytes_)) {
        desynchronised_ = true;
        bad_length_ = length;
        break;
      }
      need_ = kHeaderBytes + ceil8(static_cast<std::size_t>(length) - kHeaderBytes);
      if (need_ > have_) continue;
    }
    RawMessage message;
    message.time.seconds = detail::load_i32(buffer_.data() + 4);
    message.time.microseconds = detail::load_i32(buffer_.data() + 8);
    message.sender = detail::load_i32(buffer_.data() + 12);
    message.type = detail::load_i32(buffer_.data() + 16);
    message.payload = buffer_.data() + kHeaderBytes;
    message.payload_bytes = static_cast<std::size_t>(length) - kHeaderBytes;
    have_ = 0;
    need_ = kHeaderBytes;
    ++messages_;
    on_message(message);
  }
  return !desynchronised_;
}

}  // namespace cover::vrpn
