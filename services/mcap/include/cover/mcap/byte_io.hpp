#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace cover::mcap {

using Bytes = std::vector<std::uint8_t>;

// Appends MCAP's primitive encodings (little-endian integers, uint32-prefixed strings and
// byte arrays) to a buffer.
class ByteWriter {
 public:
  explicit ByteWriter(Bytes& out) : out_(out) {}
  void u8(std::uint8_t value) { out_.push_back(value); }
  void u16(std::uint16_t value) { little_endian(value, 2); }
  void u32(std::uint32_t value) { little_endian(value, 4); }
  void u64(std::uint64_t value) { little_endian(value, 8); }
  void string(const std::string& text);  // uint32 length | bytes
  void raw(const void* data, std::size_t size);
  // Overwrites the uint32 / uint64 at `offset` (a length known only after its content).
  void patch_u32(std::size_t offset, std::uint32_t value);
  void patch_u64(std::size_t offset, std::uint64_t value);
  std::size_t size() const { return out_.size(); }

 private:
  void little_endian(std::uint64_t value, int bytes);
  Bytes& out_;
};

// Reads the same encodings from a bounded span; every read past the end fails (returns
// false and stays failed) instead of touching memory outside the span.
class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  bool u8(std::uint8_t& value);
  bool u16(std::uint16_t& value);
  bool u32(std::uint32_t& value);
  bool u64(std::uint64_t& value);
  bool string(std::string& text);
  // A view of the next `size` bytes, consumed.
  bool span(std::size_t size, const std::uint8_t*& start);
  std::size_t position() const { return position_; }
  std::size_t remaining() const { return size_ - position_; }
  bool ok() const { return ok_; }

 private:
  bool little_endian(std::uint64_t& value, int bytes);
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t position_ = 0;
  bool ok_ = true;
};

}  // namespace cover::mcap
