#pragma once

#include <cstdint>
#include <optional>

#include "cover/mavlink/frame.hpp"
#include "cover/mavlink/signing.hpp"

namespace cover::mavlink {

// Writes v2 frames as one sender (system, component), counting its sequence number.
// Trims the payload's trailing zeros (never below 1 byte), as v2 senders do; signs when
// given a key.
class Encoder {
 public:
  Encoder(std::uint8_t system_id, std::uint8_t component_id,
          std::optional<SigningKey> signing_key = std::nullopt);

  // `Message` is one of messages.hpp's structs.
  template <typename Message>
  EncodedFrame encode(const Message& message) {
    std::array<std::uint8_t, kMaxPayloadLength> payload{};
    message.pack(payload.data());
    return frame(Message::kId, Message::kCrcExtra, payload.data(), Message::kPayloadLength);
  }

  // A frame of any id from a full (untrimmed) payload.
  EncodedFrame frame(std::uint32_t message_id, std::uint8_t crc_extra, const std::uint8_t* payload,
                     std::size_t payload_length);
  // Speaks as another sender from the next frame on, its sequence number running on: a
  // companion that learns its autopilot's system id must not look like 255 lost frames to a
  // receiver counting gaps per sender.
  void set_sender(std::uint8_t system_id, std::uint8_t component_id) {
    system_id_ = system_id;
    component_id_ = component_id;
  }
  std::uint8_t system_id() const { return system_id_; }
  std::uint8_t component_id() const { return component_id_; }

 private:
  std::uint8_t system_id_;
  std::uint8_t component_id_;
  std::optional<SigningKey> signing_key_;
  std::uint8_t seq_ = 0;
  std::uint64_t last_signing_timestamp_ = 0;  // strictly increasing, as the spec demands
};

}  // namespace cover::mavlink
