#pragma once
// A strict reader of unchunked MCAP files (what mcap_writer.hpp writes, and any other unchunked file):
// it checks both magics, every record length and field, that the Header comes first and the Footer
// last, that messages name known channels and channels known schemas, the data-section CRC (DataEnd),
// the summary CRC (Footer), the Footer's offsets and the Statistics counts. Records of other kinds
// (indexes, attachments, metadata, opcodes it does not know) are skipped, as the specification asks.
// Chunks (uncompressed, zstd or lz4: mcap_chunk.hpp) are opened and their Schema, Channel and Message
// records read like unchunked ones, with the chunk's CRC checked. Any failure is one message naming
// the byte offset (of the chunk, for a record inside one).
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/core/mcap_records.hpp"
#include "common/core/result.hpp"

namespace slam::mcap {

// A message whose data points into the parsed bytes (valid as long as they are) or, inside a
// compressed chunk, into the uncompressed chunk its Contents keep.
struct MessageView {
  uint16_t channel_id = 0;
  uint32_t sequence = 0;
  uint64_t log_time = 0;
  uint64_t publish_time = 0;
  std::span<const uint8_t> data;
};

struct Contents {
  std::string profile;
  std::string library;
  std::map<uint16_t, Schema> schemas;
  std::map<uint16_t, Channel> channels;
  std::vector<MessageView> messages;  // in file order
  std::optional<Statistics> statistics;
  uint64_t skipped_records = 0;  // records of kinds this reader does not use
  uint64_t chunks = 0;
  // Uncompressed copies of compressed chunks, which messages in them point into (shared, so a copy
  // of the contents keeps them too).
  std::vector<std::shared_ptr<const std::vector<uint8_t>>> chunk_storage;
};

// Parses and validates a whole file held in memory.
Result<Contents> parse(std::span<const uint8_t> file);

// A file mapped read-only into memory (a recording can be larger than what one wants to copy).
class MappedFile {
 public:
  static Result<std::unique_ptr<MappedFile>> open(const std::string& path);
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  std::span<const uint8_t> bytes() const { return {data_, size_}; }

 private:
  MappedFile(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  const uint8_t* data_;
  size_t size_;
};

}  // namespace slam::mcap
