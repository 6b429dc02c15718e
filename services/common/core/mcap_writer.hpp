#pragma once
// A small MCAP writer of the unchunked format: magic, Header, then Schema and Channel records as they
// are added and Message records as they come; close() ends the data section (DataEnd with its CRC)
// and writes the summary (every Schema and Channel, Statistics, a SummaryOffset per group) and the
// Footer with the summary CRC, so indexed readers (Foxglove, @mcap/core) open the file at once.
// Not thread-safe: callers with several producer threads serialise the calls.
#include <cstdio>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/core/mcap_records.hpp"
#include "common/core/result.hpp"

namespace slam::mcap {

class Writer {
 public:
  // Creates (truncates) `path` and writes the magic and the Header (profile "": no well-known
  // profile; `library` names the writer).
  static Result<std::unique_ptr<Writer>> create(const std::string& path, std::string_view library);
  // Closes the file; without an earlier close() it lacks the summary and the trailing magic.
  ~Writer();
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  // Ids are assigned from 1 in call order.
  Result<uint16_t> add_schema(std::string_view name, std::string_view encoding, std::string_view data);
  // schema_id 0 means no schema; otherwise it must come from add_schema.
  Result<uint16_t> add_channel(uint16_t schema_id, std::string_view topic, std::string_view message_encoding,
                               const std::map<std::string, std::string>& metadata = {});
  // Sequence numbers count per channel from 1. Times are nanoseconds since the Unix epoch.
  Status write_message(uint16_t channel_id, uint64_t log_time, uint64_t publish_time,
                       std::span<const uint8_t> data);
  // Writes DataEnd, the summary, the Footer and the trailing magic, and closes the file.
  Status close();

  uint64_t message_count() const { return stats_.message_count; }
  uint64_t bytes_written() const { return offset_; }

 private:
  Writer(std::FILE* file, std::string path) : file_(file), path_(std::move(path)) {}
  // Appends `bytes` to the file; data-section bytes also go into the data CRC.
  Status emit(std::span<const uint8_t> bytes, bool data_section);
  Status emit_record(Opcode op, std::span<const uint8_t> content, bool data_section);

  std::FILE* file_;
  std::string path_;
  uint64_t offset_ = 0;
  uint32_t data_crc_ = 0;
  bool closed_ = false;
  std::vector<Schema> schemas_;
  std::vector<Channel> channels_;
  std::vector<uint32_t> sequences_;  // per channel (index = id - 1)
  Statistics stats_;
};

}  // namespace slam::mcap
