// MCAP chunk decompression (mcap_chunk.hpp). SLAM_HAVE_ZSTD / SLAM_HAVE_LZ4 are set by CMake when
// the libraries were found; without them such chunks are refused by name.
#include "common/core/mcap_chunk.hpp"

#include <string>

#ifdef SLAM_HAVE_ZSTD
#include <zstd.h>
#endif
#ifdef SLAM_HAVE_LZ4
#include <lz4frame.h>
#endif

namespace slam::mcap {

namespace {

Error size_mismatch(std::string_view compression, uint64_t got, uint64_t expected) {
  return Error{std::string(compression) + " chunk uncompresses to " + std::to_string(got) +
               " bytes, its header says " + std::to_string(expected)};
}

#ifdef SLAM_HAVE_ZSTD
Result<ChunkRecords> unzstd(std::span<const uint8_t> in, uint64_t size) {
  auto out = std::make_shared<std::vector<uint8_t>>(size);
  const size_t n = ZSTD_decompress(out->data(), out->size(), in.data(), in.size());
  if (ZSTD_isError(n)) return Error{std::string("zstd chunk does not decompress: ") + ZSTD_getErrorName(n)};
  if (n != size) return size_mismatch("zstd", n, size);
  return ChunkRecords{*out, out};
}
#endif

#ifdef SLAM_HAVE_LZ4
Result<ChunkRecords> unlz4(std::span<const uint8_t> in, uint64_t size) {
  LZ4F_dctx* context = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&context, LZ4F_VERSION)))
    return Error{"lz4: no decompression context"};
  auto out = std::make_shared<std::vector<uint8_t>>(size);
  size_t in_at = 0, out_at = 0;
  std::string failure;
  for (;;) {
    size_t in_n = in.size() - in_at, out_n = out->size() - out_at;
    const size_t hint =
        LZ4F_decompress(context, out->data() + out_at, &out_n, in.data() + in_at, &in_n, nullptr);
    in_at += in_n;
    out_at += out_n;
    if (LZ4F_isError(hint)) {
      failure = std::string("lz4 chunk does not decompress: ") + LZ4F_getErrorName(hint);
      break;
    }
    if (hint == 0) break;  // the frame is complete
    if (in_n == 0 && out_n == 0) {
      failure = out_at == out->size() ? "lz4 chunk uncompresses to more bytes than its header says"
                                      : "lz4 chunk is truncated";
      break;
    }
  }
  LZ4F_freeDecompressionContext(context);
  if (!failure.empty()) return Error{failure};
  if (out_at != size) return size_mismatch("lz4", out_at, size);
  return ChunkRecords{*out, out};
}
#endif

}  // namespace

Result<ChunkRecords> chunk_records(std::string_view compression, std::span<const uint8_t> records,
                                   uint64_t uncompressed_size) {
  if (compression.empty()) {
    if (records.size() != uncompressed_size)
      return size_mismatch("uncompressed", records.size(), uncompressed_size);
    return ChunkRecords{records, nullptr};
  }
  if (uncompressed_size > kMaxChunkBytes)
    return Error{"chunk of " + std::to_string(uncompressed_size) + " bytes uncompressed, more than the " +
                 std::to_string(kMaxChunkBytes) + " this reader accepts"};
#ifdef SLAM_HAVE_ZSTD
  if (compression == "zstd") return unzstd(records, uncompressed_size);
#endif
#ifdef SLAM_HAVE_LZ4
  if (compression == "lz4") return unlz4(records, uncompressed_size);
#endif
  if (compression == "zstd" || compression == "lz4")
    return Error{std::string(compression) + " chunks need lib" + std::string(compression) +
                 " (this build was made without it)"};
  return Error{"unknown chunk compression '" + std::string(compression) + "'"};
}

}  // namespace slam::mcap
