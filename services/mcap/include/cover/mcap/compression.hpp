#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "cover/mcap/byte_io.hpp"

namespace cover::mcap {

// Chunk compression; MCAP names them "zstd", "lz4" (LZ4 frame format) and "" (none).
enum class Compression { None, Lz4, Zstd };

// The MCAP name ("" for None).
std::string_view compression_name(Compression compression);
// "none" / "lz4" / "zstd" (the command-line spelling) and MCAP's own "" for none.
std::optional<Compression> parse_compression(std::string_view name);

// Appends `size` bytes of `data` compressed to `out`.
void compress(Compression compression, const std::uint8_t* data, std::size_t size, Bytes& out);

// Decompresses into `out` (resized to `uncompressed_size`); on failure returns false with
// the codec's reason in `error` (corrupt data, wrong size, unknown compression).
bool decompress(std::string_view compression, const std::uint8_t* data, std::size_t size,
                std::size_t uncompressed_size, Bytes& out, std::string& error);

}  // namespace cover::mcap
