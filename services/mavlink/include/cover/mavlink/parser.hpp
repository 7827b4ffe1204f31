#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>

#include "cover/mavlink/frame.hpp"
#include "cover/mavlink/signing.hpp"

namespace cover::mavlink {

// What a stream parser saw, counted since construction. Every candidate (a start marker
// followed by a header) is delivered (`frames`), skipped whole as a frame of a message the
// codec does not know (`unknown_frames`), or counted in exactly one refusal count; a
// refused candidate gives back every byte after its start marker to be scanned again. So
// every byte fed is exactly one of: a byte of a delivered or skipped frame, the start
// marker of a refused candidate, a garbage byte, or still pending:
//   bytes fed == delivered frame bytes + unknown_frame_bytes + refusals() + garbage_bytes
//                + pending_bytes().
// An autopilot streams dozens of message types a companion does not read (PX4 about 25):
// those are traffic, not errors, and their sequence numbers count as received.
struct ParserStats {
  std::uint64_t candidates = 0;     // judged: frames + unknown_frames + refusals()
  std::uint64_t frames = 0;         // delivered (checksum ok; signature ok if checked)
  std::uint64_t garbage_bytes = 0;  // bytes skipped while looking for a start marker
  std::uint64_t crc_errors = 0;     // known id, checksum wrong
  // A frame of an id not in the message table, skipped whole: its checksum cannot be checked
  // (no CRC_EXTRA), so it counts as a frame only when a start marker follows it.
  std::uint64_t unknown_frames = 0;
  std::uint64_t unknown_frame_bytes = 0;
  std::uint64_t unknown_ids = 0;       // an unknown id not followed by a start marker: refused
  std::uint64_t bad_length = 0;        // a known id with a payload longer than it can be
                                       // (v1) or an incompat flag we do not know
  std::uint64_t signature_errors = 0;  // signed, key configured, signature wrong
  std::uint64_t unsigned_refused = 0;  // key configured and require_signed, frame unsigned
  std::uint64_t sequence_gaps = 0;     // frames lost, from each sender's sequence numbers
  std::uint64_t errors() const {
    return crc_errors + bad_length + signature_errors + unsigned_refused;
  }
  std::uint64_t refusals() const { return errors() + unknown_ids; }
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
  // Bytes of a frame begun but not complete yet.
  std::size_t pending_bytes() const { return buffered_; }

 private:
  enum class Verdict { NeedMore, Deliver, Refuse, Skip };
  std::size_t header_length() const;
  Verdict judge_header();
  Verdict judge_frame();
  Verdict judge_unknown();
  std::size_t bytes_to_judge() const;
  void deliver(const FrameHandler& on_frame);
  void settle(const FrameHandler& on_frame);
  void drop_until_magic(std::size_t from);
  void count_sequence(std::uint8_t system_id, std::uint8_t component_id, std::uint8_t seq);

  ParserOptions options_;
  ParserStats stats_;
  // buffer_[0, buffered_) is one candidate frame: it starts with a start marker.
  // One byte more than a frame: an unknown frame is judged by the byte that follows it.
  std::array<std::uint8_t, kMaxFrameLength + 1> buffer_{};
  std::size_t buffered_ = 0;
  std::size_t frame_length_ = 0;   // the candidate's full length once its header is judged
  std::uint8_t crc_extra_ = 0;     // of the candidate's message, once its header is judged
  std::uint8_t known_length_ = 0;  // the candidate's message's full payload length
  bool unknown_ = false;           // the candidate's id is not in the message table
  Frame frame_;                    // the frame being delivered, reused
  std::array<std::int16_t, 256 * 256> last_seq_{};  // per (system, component), -1: none
};

}  // namespace cover::mavlink
