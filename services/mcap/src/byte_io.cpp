#include "cover/mcap/byte_io.hpp"

namespace cover::mcap {

void ByteWriter::little_endian(std::uint64_t value, int bytes) {
  for (int i = 0; i < bytes; ++i) out_.push_back(static_cast<std::uint8_t>(value >> (8 * i)));
}

void ByteWriter::string(const std::string& text) {
  u32(static_cast<std::uint32_t>(text.size()));
  raw(text.data(), text.size());
}

void ByteWriter::raw(const void* data, std::size_t size) {
  const auto* bytes = static_cast<const std::uint8_t*>(data);
  out_.insert(out_.end(), bytes, bytes + size);
}

void ByteWriter::patch_u32(std::size_t offset, std::uint32_t value) {
  for (int i = 0; i < 4; ++i) out_[offset + i] = static_cast<std::uint8_t>(value >> (8 * i));
}

void ByteWriter::patch_u64(std::size_t offset, std::uint64_t value) {
  for (int i = 0; i < 8; ++i) out_[offset + i] = static_cast<std::uint8_t>(value >> (8 * i));
}

bool ByteReader::little_endian(std::uint64_t& value, int bytes) {
  if (!ok_ || remaining() < static_cast<std::size_t>(bytes)) return ok_ = false;
  value = 0;
  for (int i = 0; i < bytes; ++i) value |= std::uint64_t{data_[position_ + i]} << (8 * i);
  position_ += bytes;
  return true;
}

bool ByteReader::u8(std::uint8_t& value) {
  std::uint64_t v = 0;
  if (!little_endian(v, 1)) return false;
  value = static_cast<std::uint8_t>(v);
  return true;
}

bool ByteReader::u16(std::uint16_t& value) {
  std::uint64_t v = 0;
  if (!little_endian(v, 2)) return false;
  value = static_cast<std::uint16_t>(v);
  return true;
}

bool ByteReader::u32(std::uint32_t& value) {
  std::uint64_t v = 0;
  if (!little_endian(v, 4)) return false;
  value = static_cast<std::uint32_t>(v);
  return true;
}

bool ByteReader::u64(std::uint64_t& value) {
  return little_endian(value, 8);
}

bool ByteReader::string(std::string& text) {
  std::uint32_t length = 0;
  const std::uint8_t* start = nullptr;
  if (!u32(length) || !span(length, start)) return false;
  text.assign(reinterpret_cast<const char*>(start), length);
  return true;
}

bool ByteReader::span(std::size_t size, const std::uint8_t*& start) {
  if (!ok_ || remaining() < size) return ok_ = false;
  start = data_ + position_;
  position_ += size;
  return true;
}

}  // namespace cover::mcap
