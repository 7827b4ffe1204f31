#include "cover/mavlink/parser.hpp"

#include <algorithm>
#include <cstring>

#include "cover/mavlink/crc.hpp"
#include "cover/mavlink/message_table.hpp"

namespace cover::mavlink {

namespace {

bool is_magic(std::uint8_t byte) {
  return byte == kMagicV2 || byte == kMagicV1;
}

std::uint64_t read_le48(const std::uint8_t* bytes) {
  std::uint64_t value = 0;
  for (std::size_t i = 0; i < 6; ++i) value |= static_cast<std::uint64_t>(bytes[i]) << (8 * i);
  return value;
}

}  // namespace

StreamParser::StreamParser(ParserOptions options) : options_(options) {
  last_seq_.fill(-1);
}

void StreamParser::feed(const std::uint8_t* data, std::size_t size, const FrameHandler& on_frame) {
  std::size_t i = 0;
  while (i < size) {
    if (buffered_ == 0) {
      const std::size_t start = i;
      while (i < size && !is_magic(data[i])) ++i;
      stats_.garbage_bytes += i - start;
      if (i == size) return;
      buffer_[0] = data[i++];
      buffered_ = 1;
      frame_length_ = 0;
      continue;
    }
    // Copy only up to the next decision point (header, then whole frame), so the buffer
    // never holds bytes past the candidate unless a refusal handed them back.
    const std::size_t target = frame_length_ != 0 ? bytes_to_judge() : header_length();
    const std::size_t take = std::min(target - buffered_, size - i);
    std::memcpy(buffer_.data() + buffered_, data + i, take);
    buffered_ += take;
    i += take;
    settle(on_frame);
  }
}

void StreamParser::reset() {
  stats_.garbage_bytes += buffered_;
  buffered_ = 0;
  frame_length_ = 0;
}

std::size_t StreamParser::header_length() const {
  return buffer_[0] == kMagicV2 ? kHeaderLengthV2 : kHeaderLengthV1;
}

// Judges every candidate the buffer holds completely, until it needs more bytes.
void StreamParser::settle(const FrameHandler& on_frame) {
  while (buffered_ > 0) {
    if (frame_length_ == 0) {
      if (buffered_ < header_length()) return;
      if (judge_header() == Verdict::Refuse) {
        drop_until_magic(1);
        continue;
      }
    }
    if (buffered_ < bytes_to_judge()) return;
    const Verdict verdict = unknown_ ? judge_unknown() : judge_frame();
    if (verdict == Verdict::Refuse) {
      drop_until_magic(1);
      continue;
    }
    if (verdict == Verdict::Deliver) deliver(on_frame);
    drop_until_magic(frame_length_);
  }
}

// Decides what can be decided from the header alone: a flag or id we cannot check, or a
// v1 payload too long for its message. Otherwise learns the frame's length.
StreamParser::Verdict StreamParser::judge_header() {
  const bool v2 = buffer_[0] == kMagicV2;
  const std::uint8_t length = buffer_[1];
  const std::uint8_t incompat = v2 ? buffer_[2] : 0;
  const std::uint32_t id = v2 ? (buffer_[7] | (buffer_[8] << 8) | (buffer_[9] << 16)) : buffer_[5];
  const auto refuse = [this](std::uint64_t& count) {
    ++count;
    ++stats_.candidates;
    return Verdict::Refuse;
  };
  if ((incompat & ~kIncompatSigned) != 0) return refuse(stats_.bad_length);
  const std::optional<MessageInfo> info = message_info(id);
  unknown_ = !info;
  if (info) {
    if (!v2 && length > info->payload_length) return refuse(stats_.bad_length);
    crc_extra_ = info->crc_extra;
    known_length_ = info->payload_length;
  }
  const bool is_signed = (incompat & kIncompatSigned) != 0;
  frame_length_ = header_length() + length + kChecksumLength + (is_signed ? kSignatureLength : 0);
  return Verdict::NeedMore;
}

// Checks a complete candidate: checksum, then signature or its absence.
StreamParser::Verdict StreamParser::judge_frame() {
  ++stats_.candidates;
  const std::size_t checked = header_length() + buffer_[1];
  std::uint16_t crc = crc_accumulate(buffer_.data() + 1, checked - 1, kCrcInit);
  crc = crc_accumulate(crc_extra_, crc);
  const std::uint16_t wire =
      static_cast<std::uint16_t>(buffer_[checked] | (buffer_[checked + 1] << 8));
  if (crc != wire) {
    ++stats_.crc_errors;
    return Verdict::Refuse;
  }
  if (!options_.signing_key) return Verdict::Deliver;
  const bool is_signed = buffer_[0] == kMagicV2 && (buffer_[2] & kIncompatSigned) != 0;
  if (!is_signed) {
    if (!options_.require_signed) return Verdict::Deliver;
    ++stats_.unsigned_refused;
    return Verdict::Refuse;
  }
  const std::uint8_t* tail = buffer_.data() + checked + kChecksumLength;
  const auto expected = signature_of(*options_.signing_key, buffer_.data(),
                                     checked + kChecksumLength, tail[0], read_le48(tail + 1));
  if (!std::equal(expected.begin(), expected.end(), tail + 7)) {
    ++stats_.signature_errors;
    return Verdict::Refuse;
  }
  return Verdict::Deliver;
}

// An unknown frame's length is all we can check: it is one when the next byte starts a
// frame. A false start marker (inside garbage or a broken frame) rarely lines up so.
std::size_t StreamParser::bytes_to_judge() const {
  return unknown_ ? frame_length_ + 1 : frame_length_;
}

StreamParser::Verdict StreamParser::judge_unknown() {
  ++stats_.candidates;
  if (!is_magic(buffer_[frame_length_])) {
    ++stats_.unknown_ids;
    return Verdict::Refuse;
  }
  const bool v2 = buffer_[0] == kMagicV2;
  ++stats_.unknown_frames;
  stats_.unknown_frame_bytes += frame_length_;
  count_sequence(buffer_[v2 ? 5 : 3], buffer_[v2 ? 6 : 4], buffer_[v2 ? 4 : 2]);
  return Verdict::Skip;
}

void StreamParser::deliver(const FrameHandler& on_frame) {
  const bool v2 = buffer_[0] == kMagicV2;
  const std::size_t header = header_length();
  const std::uint8_t wire_length = buffer_[1];
  Frame& f = frame_;
  f.version = v2 ? 2 : 1;
  f.incompat_flags = v2 ? buffer_[2] : 0;
  f.compat_flags = v2 ? buffer_[3] : 0;
  f.seq = buffer_[v2 ? 4 : 2];
  f.system_id = buffer_[v2 ? 5 : 3];
  f.component_id = buffer_[v2 ? 6 : 4];
  f.message_id = v2 ? (buffer_[7] | (buffer_[8] << 8) | (buffer_[9] << 16)) : buffer_[5];
  // A longer payload than we know carries newer extensions: keep what we understand.
  f.payload_length = std::min(wire_length, known_length_);
  std::memcpy(f.payload.data(), buffer_.data() + header, f.payload_length);
  std::memset(f.payload.data() + f.payload_length, 0, f.payload.size() - f.payload_length);
  if (f.is_signed()) {
    std::memcpy(f.signature.data(), buffer_.data() + header + wire_length + kChecksumLength,
                kSignatureLength);
  } else {
    f.signature.fill(0);
  }
  ++stats_.frames;
  count_sequence(f.system_id, f.component_id, f.seq);
  on_frame(f);
}

// Consumes buffer_[0, from) and hunts for the next start marker in the rest, counting
// what it skips as garbage; what remains becomes the new candidate.
void StreamParser::drop_until_magic(std::size_t from) {
  std::size_t next = from;
  while (next < buffered_ && !is_magic(buffer_[next])) ++next;
  stats_.garbage_bytes += next - from;
  std::memmove(buffer_.data(), buffer_.data() + next, buffered_ - next);
  buffered_ -= next;
  frame_length_ = 0;
}

void StreamParser::count_sequence(std::uint8_t system_id, std::uint8_t component_id,
                                  std::uint8_t seq) {
  std::int16_t& last = last_seq_[(static_cast<std::size_t>(system_id) << 8) | component_id];
  if (last >= 0) {
    stats_.sequence_gaps += static_cast<std::uint8_t>(seq - last - 1);
  }
  last = seq;
}

}  // namespace cover::mavlink
