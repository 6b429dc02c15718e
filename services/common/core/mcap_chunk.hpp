#pragma once
// The records inside an MCAP Chunk, uncompressed. Chunks come from most writers other than this
// project's own (ros2 bag record, the mcap CLI, @mcap/core): uncompressed, zstd or lz4 (the LZ4
// frame format), the last two only when the build found libzstd / liblz4.
#include <cstdint>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "common/core/result.hpp"

namespace slam::mcap {

// A chunk larger than this once uncompressed is refused: writers cut chunks at about 1 MB, and a
// bound keeps a forged size from allocating unboundedly.
inline constexpr uint64_t kMaxChunkBytes = uint64_t{64} << 20;

struct ChunkRecords {
  std::span<const uint8_t> bytes;                       // the records
  std::shared_ptr<const std::vector<uint8_t>> storage;  // holds `bytes` when they were decompressed
};

// `records` as the Chunk stores them (compressed with `compression`), checked to uncompress to
// exactly `uncompressed_size` bytes. Uncompressed records are not copied.
Result<ChunkRecords> chunk_records(std::string_view compression, std::span<const uint8_t> records,
                                   uint64_t uncompressed_size);

}  // namespace slam::mcap
