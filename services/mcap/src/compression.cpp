#include "cover/mcap/compression.hpp"

#include <lz4frame.h>
#include <zstd.h>

#include <memory>

namespace cover::mcap {
namespace {

// Level 1: the recorder runs next to the control loop; zstd -1 already takes CDR samples
// to a fraction of their size (docs/benchmarks.md, cover-bench record).
constexpr int kZstdLevel = 1;
constexpr std::size_t kMaxUnsizedZstdBytes = 64 * 1024 * 1024;

void compress_zstd(const std::uint8_t* data, std::size_t size, Bytes& out) {
  const std::size_t start = out.size();
  out.resize(start + ZSTD_compressBound(size));
  const std::size_t written =
      ZSTD_compress(out.data() + start, out.size() - start, data, size, kZstdLevel);
  // Cannot fail with a ZSTD_compressBound buffer; store nothing rather than garbage.
  out.resize(ZSTD_isError(written) ? start : start + written);
}

void compress_lz4(const std::uint8_t* data, std::size_t size, Bytes& out) {
  LZ4F_preferences_t preferences{};
  preferences.frameInfo.contentSize = size;
  const std::size_t start = out.size();
  out.resize(start + LZ4F_compressFrameBound(size, &preferences));
  const std::size_t written =
      LZ4F_compressFrame(out.data() + start, out.size() - start, data, size, &preferences);
  out.resize(LZ4F_isError(written) ? start : start + written);
}

bool decompress_zstd(const std::uint8_t* data, std::size_t size, Bytes& out, std::string& error) {
  const std::size_t written = ZSTD_decompress(out.data(), out.size(), data, size);
  if (ZSTD_isError(written)) {
    error = std::string("zstd: ") + ZSTD_getErrorName(written);
    return false;
  }
  if (written != out.size()) {
    error = "zstd: " + std::to_string(written) + " bytes decompressed, the chunk declares " +
            std::to_string(out.size());
    return false;
  }
  return true;
}

bool decompress_lz4(const std::uint8_t* data, std::size_t size, Bytes& out, std::string& error) {
  LZ4F_dctx* raw_context = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&raw_context, LZ4F_VERSION))) {
    error = "lz4: no decompression context";
    return false;
  }
  std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> context(
      raw_context, &LZ4F_freeDecompressionContext);
  std::size_t in_done = 0;
  std::size_t out_done = 0;
  while (in_done < size) {
    std::size_t in_size = size - in_done;
    std::size_t out_size = out.size() - out_done;
    const std::size_t hint = LZ4F_decompress(context.get(), out.data() + out_done, &out_size,
                                             data + in_done, &in_size, nullptr);
    if (LZ4F_isError(hint)) {
      error = std::string("lz4: ") + LZ4F_getErrorName(hint);
      return false;
    }
    in_done += in_size;
    out_done += out_size;
    if (hint == 0) break;  // frame complete
    if (in_size == 0 && out_size == 0) break;
  }
  if (out_done != out.size()) {
    error = "lz4: " + std::to_string(out_done) + " bytes decompressed, the chunk declares " +
            std::to_string(out.size());
    return false;
  }
  return true;
}

}  // namespace

std::string_view compression_name(Compression compression) {
  switch (compression) {
    case Compression::Lz4:
      return "lz4";
    case Compression::Zstd:
      return "zstd";
    case Compression::None:
      break;
  }
  return "";
}

std::optional<Compression> parse_compression(std::string_view name) {
  if (name == "none" || name.empty()) return Compression::None;
  if (name == "lz4") return Compression::Lz4;
  if (name == "zstd") return Compression::Zstd;
  return std::nullopt;
}

void compress(Compression compression, const std::uint8_t* data, std::size_t size, Bytes& out) {
  switch (compression) {
    case Compression::Zstd:
      compress_zstd(data, size, out);
      return;
    case Compression::Lz4:
      compress_lz4(data, size, out);
      return;
    case Compression::None:
      out.insert(out.end(), data, data + size);
      return;
  }
}

namespace {

// Checked before allocating: a corrupt size field must not make a reader allocate what
// the compressed bytes cannot hold.
bool plausible_size(std::string_view compression, const std::uint8_t* data, std::size_t size,
                    std::size_t uncompressed_size, std::string& error) {
  if (compression == "lz4" && uncompressed_size > size * 256 + 64) {
    error = "lz4: " + std::to_string(size) + " bytes cannot hold the " +
            std::to_string(uncompressed_size) + " the chunk declares";
    return false;
  }
  if (compression == "zstd") {
    const unsigned long long content = ZSTD_getFrameContentSize(data, size);
    // A frame without its size (streaming writers) gets a cap instead: chunks are ~1 MiB.
    if (content == ZSTD_CONTENTSIZE_UNKNOWN && uncompressed_size > kMaxUnsizedZstdBytes) {
      error = "zstd: a frame of unknown size cannot be trusted with the " +
              std::to_string(uncompressed_size) + " bytes the chunk declares";
      return false;
    }
    if (content != ZSTD_CONTENTSIZE_UNKNOWN && content != uncompressed_size) {
      error = content == ZSTD_CONTENTSIZE_ERROR
                  ? std::string("zstd: not a zstd frame")
                  : "zstd: the frame holds " + std::to_string(content) +
                        " bytes, the chunk declares " + std::to_string(uncompressed_size);
      return false;
    }
  }
  return true;
}

}  // namespace

bool decompress(std::string_view compression, const std::uint8_t* data, std::size_t size,
                std::size_t uncompressed_size, Bytes& out, std::string& error) {
  if (!compression.empty() && compression != "zstd" && compression != "lz4") {
    error = "unknown compression '" + std::string(compression) + "'";
    return false;
  }
  if (!plausible_size(compression, data, size, uncompressed_size, error)) return false;
  if (compression.empty()) {
    if (size != uncompressed_size) {
      error = "uncompressed chunk of " + std::to_string(size) + " bytes declares " +
              std::to_string(uncompressed_size);
      return false;
    }
    out.assign(data, data + size);
    return true;
  }
  out.assign(uncompressed_size, 0);
  if (compression == "zstd") return decompress_zstd(data, size, out, error);
  return decompress_lz4(data, size, out, error);
}

}  // namespace cover::mcap
