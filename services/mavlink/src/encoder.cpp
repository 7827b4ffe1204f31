#include "cover/mavlink/encoder.hpp"

#include <chrono>
#include <cstring>

#include "cover/mavlink/crc.hpp"

namespace cover::mavlink {

namespace {

std::int64_t unix_now_us() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

// v2 senders drop the payload's trailing zeros but always keep its first byte.
std::size_t trimmed_length(const std::uint8_t* payload, std::size_t length) {
  while (length > 1 && payload[length - 1] == 0) --length;
  return length;
}

}  // namespace

Encoder::Encoder(std::uint8_t system_id, std::uint8_t component_id,
                 std::optional<SigningKey> signing_key)
    : system_id_(system_id), component_id_(component_id), signing_key_(signing_key) {}

EncodedFrame Encoder::frame(std::uint32_t message_id, std::uint8_t crc_extra,
                            const std::uint8_t* payload, std::size_t payload_length) {
  EncodedFrame out;
  if (payload_length > kMaxPayloadLength) payload_length = kMaxPayloadLength;
  const std::size_t length = payload_length == 0 ? 0 : trimmed_length(payload, payload_length);
  std::uint8_t* b = out.bytes.data();
  b[0] = kMagicV2;
  b[1] = static_cast<std::uint8_t>(length);
  b[2] = signing_key_ ? kIncompatSigned : 0;
  b[3] = 0;
  b[4] = seq_++;
  b[5] = system_id_;
  b[6] = component_id_;
  b[7] = static_cast<std::uint8_t>(message_id);
  b[8] = static_cast<std::uint8_t>(message_id >> 8);
  b[9] = static_cast<std::uint8_t>(message_id >> 16);
  if (length > 0) std::memcpy(b + kHeaderLengthV2, payload, length);
  std::size_t size = kHeaderLengthV2 + length;
  std::uint16_t crc = crc_accumulate(b + 1, size - 1, kCrcInit);
  crc = crc_accumulate(crc_extra, crc);
  b[size++] = static_cast<std::uint8_t>(crc);
  b[size++] = static_cast<std::uint8_t>(crc >> 8);
  if (signing_key_) {
    // Strictly increasing even when the clock steps back or two frames share a tick.
    std::uint64_t timestamp = signing_timestamp(unix_now_us());
    if (timestamp <= last_signing_timestamp_) timestamp = last_signing_timestamp_ + 1;
    last_signing_timestamp_ = timestamp;
    const auto signature = signature_of(*signing_key_, b, size, signing_key_->link_id, timestamp);
    b[size++] = signing_key_->link_id;
    for (std::size_t i = 0; i < 6; ++i) b[size++] = static_cast<std::uint8_t>(timestamp >> (8 * i));
    std::memcpy(b + size, signature.data(), signature.size());
    size += signature.size();
  }
  out.size = size;
  return out;
}

}  // namespace cover::mavlink
