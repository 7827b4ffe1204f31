#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>

#include "cover/mavlink/frame.hpp"
#include "cover/mavlink/signing.hpp"

namespace cover::mavlink {

// What a stream parser saw, counted since construction. Every byte read ends up in a
// frame, or in exactly one of the refusal counts' frames, or in `garbage_bytes`.
struct ParserStats {
  std::uint64_t frames = 0;             // delivered (checksum ok; signature ok if checked)
  std::uint64_t garbage_bytes = 0;      // bytes skipped while looking for a start marker
  std::uint64_t crc_errors = 0;         // known id, checksum wrong
  std::uint64_t unknown_ids = 0;        // id not in the message table (not delivered)
  std::uint64_t bad_length = 0;         // a known id with a payload longer than it can be
                                        // (v1) or an incompat flag we do not know
  std::uint64_t signature_errors = 0;   // signed, key configured, signature wrong
  std::uint64_t unsigned_refused = 0;   // key configured and require_signed, frame unsigned
  std::uint64_t sequence_gaps = 0;      // frames lost, from each sender's sequence numbers
  std::uint64_t errors() const {
    return crc_errors + bad_length + signature_errors + unsigned_refused;
  }
};

struct ParserOptions {
  // With a key, signed frames are checked against it (a wrong signature is refused);
  // without, signed frames are accepted unchecked (the signature is not ours to judge).
  std::optional<SigningKey> signing_key;
  bool require_signed = false;  // with a key: refuse unsigned frames
};

// A MAVLink byte stream (v1 and v2, signed or not) to frames. Survives anything: garbage
// between frames, wrong checksums, unknown ids, truncated and oversized frames; a
// refused candidate frame resynchronises on the byte after its start marker, so a real
// frame hidden inside a broken one is still found. Never allocates after construction.
class StreamParser {
 public:
  using FrameHandler = std::function<void(const Frame&)>;
  explicit StreamParser(ParserOptions options = {});

  // Feeds bytes; `on_frame` runs for every frame completed by them, in order.
  void feed(const std::uint8_t* data, std::size_t size, const FrameHandler& on_frame);
  // Forgets a partial frame (the link was reopened).
  void reset();
  const ParserStats& stats() const { return stats_; }

 private:
  // Implementation-defined state (the codec helper fills this in).
  struct Impl;
  ParserOptions options_;
  ParserStats stats_;
  std::array<std::uint8_t, kMaxFrameLength> buffer_{};
  std::size_t buffered_ = 0;
  std::array<std::int16_t, 256 * 256> last_seq_{};  // per (system, component), -1: none
};

}  // namespace cover::mavlink
