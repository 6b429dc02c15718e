#pragma once
// The MCAP records this project writes and reads (unchunked files only), as plain data. Layouts follow
// the MCAP specification: every record is opcode (uint8), content length (uint64), content; integers
// little-endian; strings and byte arrays prefixed with a uint32 length; maps with a uint32 byte length.
#include <array>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace slam::mcap {

// Both ends of every file: 0x89 "MCAP" '0' "\r\n".
inline constexpr std::array<uint8_t, 8> kMagic{0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
// opcode + content length.
inline constexpr size_t kRecordPrefix = 9;
// Footer content: summary_start, summary_offset_start, summary_crc.
inline constexpr size_t kFooterContent = 20;

enum class Opcode : uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kAttachment = 0x09,
  kAttachmentIndex = 0x0A,
  kStatistics = 0x0B,
  kMetadata = 0x0C,
  kMetadataIndex = 0x0D,
  kSummaryOffset = 0x0E,
  kDataEnd = 0x0F,
};

struct Schema {
  uint16_t id = 0;  // 0 is reserved ("no schema")
  std::string name;
  std::string encoding;  // e.g. "omgidl"
  std::string data;      // the schema text
  bool operator==(const Schema&) const = default;
};

struct Channel {
  uint16_t id = 0;
  uint16_t schema_id = 0;
  std::string topic;
  std::string message_encoding;  // e.g. "cdr"
  std::map<std::string, std::string> metadata;
  bool operator==(const Channel&) const = default;
};

struct Statistics {
  uint64_t message_count = 0;
  uint16_t schema_count = 0;
  uint32_t channel_count = 0;
  uint32_t attachment_count = 0;
  uint32_t metadata_count = 0;
  uint32_t chunk_count = 0;
  uint64_t message_start_time = 0;  // smallest log_time, 0 without messages
  uint64_t message_end_time = 0;    // largest log_time
  std::map<uint16_t, uint64_t> channel_message_counts;
  bool operator==(const Statistics&) const = default;
};

// Little-endian field encoding of record contents, and whole records.
class Encoder {
 public:
  void u8(uint8_t v) { bytes_.push_back(v); }
  void u16(uint16_t v) { le(v, 2); }
  void u32(uint32_t v) { le(v, 4); }
  void u64(uint64_t v) { le(v, 8); }
  void raw(std::span<const uint8_t> b);
  // uint32 length, then the bytes (strings and byte arrays).
  void prefixed(std::string_view s);
  // uint32 byte length of the entries, then each key and value.
  void string_map(const std::map<std::string, std::string>& m);
  // opcode, content length, content.
  void record(Opcode op, std::span<const uint8_t> content);
  const std::vector<uint8_t>& bytes() const { return bytes_; }

 private:
  void le(uint64_t v, int n) {
    for (int i = 0; i < n; ++i) bytes_.push_back(static_cast<uint8_t>(v >> (8 * i)));
  }
  std::vector<uint8_t> bytes_;
};

// CRC-32 as MCAP specifies it (the zlib / ISO-HDLC polynomial), continuing from `crc`.
uint32_t crc32(std::span<const uint8_t> bytes, uint32_t crc = 0);

}  // namespace slam::mcap
