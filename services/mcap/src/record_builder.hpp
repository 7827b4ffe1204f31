#pragma once

#include "cover/mcap/byte_io.hpp"
#include "cover/mcap/records.hpp"

namespace cover::mcap {

// Appends one record (opcode, length, content) to a buffer: begin() writes the opcode and
// a length placeholder, end() patches the length once the content is in.
class RecordBuilder {
 public:
  RecordBuilder(Bytes& out, Op op) : writer_(out) {
    writer_.u8(static_cast<std::uint8_t>(op));
    length_at_ = writer_.size();
    writer_.u64(0);
  }
  ByteWriter& content() { return writer_; }
  void end() { writer_.patch_u64(length_at_, writer_.size() - length_at_ - 8); }

 private:
  ByteWriter writer_;
  std::size_t length_at_ = 0;
};

void append_schema(Bytes& out, const Schema& schema);
void append_channel(Bytes& out, const Channel& channel);

}  // namespace cover::mcap
