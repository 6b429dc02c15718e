#include "common/core/mcap_writer.hpp"

#include <cerrno>
#include <cstring>

namespace slam::mcap {

Result<std::unique_ptr<Writer>> Writer::create(const std::string& path, std::string_view library) {
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) return Error{"cannot create " + path + ": " + std::strerror(errno)};
  std::unique_ptr<Writer> writer(new Writer(file, path));
  Encoder header;
  header.prefixed("");  // profile: none of the well-known ones (ros1, ros2) applies
  header.prefixed(library);
  SLAM_TRY(writer->emit(kMagic, true));
  SLAM_TRY(writer->emit_record(Opcode::kHeader, header.bytes(), true));
  return writer;
}

Writer::~Writer() {
  if (file_) std::fclose(file_);
}

Status Writer::emit(std::span<const uint8_t> bytes, bool data_section) {
  if (!file_ || closed_) return Error{path_ + ": the recording is closed"};
  if (bytes.empty()) return {};  // fwrite with an empty span's null data pointer is undefined
  if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size())
    return Error{"cannot write " + path_ + ": " + std::strerror(errno)};
  if (data_section) data_crc_ = crc32(bytes, data_crc_);
  offset_ += bytes.size();
  return {};
}

Status Writer::emit_record(Opcode op, std::span<const uint8_t> content, bool data_section) {
  Encoder record;
  record.record(op, content);
  return emit(record.bytes(), data_section);
}

namespace {

std::vector<uint8_t> schema_content(const Schema& s) {
  Encoder e;
  e.u16(s.id);
  e.prefixed(s.name);
  e.prefixed(s.encoding);
  e.prefixed(s.data);
  return e.bytes();
}

std::vector<uint8_t> channel_content(const Channel& c) {
  Encoder e;
  e.u16(c.id);
  e.u16(c.schema_id);
  e.prefixed(c.topic);
  e.prefixed(c.message_encoding);
  e.string_map(c.metadata);
  return e.bytes();
}

std::vector<uint8_t> statistics_content(const Statistics& s) {
  Encoder e;
  e.u64(s.message_count);
  e.u16(s.schema_count);
  e.u32(s.channel_count);
  e.u32(s.attachment_count);
  e.u32(s.metadata_count);
  e.u32(s.chunk_count);
  e.u64(s.message_start_time);
  e.u64(s.message_end_time);
  Encoder counts;
  for (const auto& [channel, n] : s.channel_message_counts) {
    counts.u16(channel);
    counts.u64(n);
  }
  e.u32(static_cast<uint32_t>(counts.bytes().size()));
  e.raw(counts.bytes());
  return e.bytes();
}

}  // namespace

Result<uint16_t> Writer::add_schema(std::string_view name, std::string_view encoding, std::string_view data) {
  if (schemas_.size() >= UINT16_MAX) return Error{path_ + ": too many schemas"};
  Schema s{static_cast<uint16_t>(schemas_.size() + 1), std::string(name), std::string(encoding),
           std::string(data)};
  SLAM_TRY(emit_record(Opcode::kSchema, schema_content(s), true));
  schemas_.push_back(std::move(s));
  stats_.schema_count = static_cast<uint16_t>(schemas_.size());
  return schemas_.back().id;
}

Result<uint16_t> Writer::add_channel(uint16_t schema_id, std::string_view topic,
                                     std::string_view message_encoding,
                                     const std::map<std::string, std::string>& metadata) {
  if (schema_id > schemas_.size()) return Error{path_ + ": unknown schema id " + std::to_string(schema_id)};
  if (channels_.size() >= UINT16_MAX) return Error{path_ + ": too many channels"};
  Channel c{static_cast<uint16_t>(channels_.size() + 1), schema_id, std::string(topic),
            std::string(message_encoding), metadata};
  SLAM_TRY(emit_record(Opcode::kChannel, channel_content(c), true));
  channels_.push_back(std::move(c));
  sequences_.push_back(0);
  stats_.channel_count = static_cast<uint32_t>(channels_.size());
  return channels_.back().id;
}

Status Writer::write_message(uint16_t channel_id, uint64_t log_time, uint64_t publish_time,
                             std::span<const uint8_t> data) {
  if (channel_id == 0 || channel_id > channels_.size())
    return Error{path_ + ": unknown channel id " + std::to_string(channel_id)};
  Encoder e;
  e.u8(static_cast<uint8_t>(Opcode::kMessage));
  e.u64(2 + 4 + 8 + 8 + data.size());
  e.u16(channel_id);
  e.u32(++sequences_[channel_id - 1]);
  e.u64(log_time);
  e.u64(publish_time);
  SLAM_TRY(emit(e.bytes(), true));
  SLAM_TRY(emit(data, true));
  if (stats_.message_count == 0 || log_time < stats_.message_start_time) stats_.message_start_time = log_time;
  if (stats_.message_count == 0 || log_time > stats_.message_end_time) stats_.message_end_time = log_time;
  ++stats_.message_count;
  ++stats_.channel_message_counts[channel_id];
  return {};
}

Status Writer::close() {
  Encoder data_end;
  data_end.u32(data_crc_);
  SLAM_TRY(emit_record(Opcode::kDataEnd, data_end.bytes(), false));

  // The summary: one group per record kind, each found again through its SummaryOffset record.
  const uint64_t summary_start = offset_;
  Encoder summary;
  Encoder offsets;
  auto group = [&](Opcode op, auto&& add_records) {
    const uint64_t start = summary_start + summary.bytes().size();
    add_records();
    const uint64_t length = summary_start + summary.bytes().size() - start;
    if (length == 0) return;
    Encoder o;
    o.u8(static_cast<uint8_t>(op));
    o.u64(start);
    o.u64(length);
    offsets.record(Opcode::kSummaryOffset, o.bytes());
  };
  group(Opcode::kSchema, [&] {
    for (const Schema& s : schemas_) summary.record(Opcode::kSchema, schema_content(s));
  });
  group(Opcode::kChannel, [&] {
    for (const Channel& c : channels_) summary.record(Opcode::kChannel, channel_content(c));
  });
  group(Opcode::kStatistics, [&] { summary.record(Opcode::kStatistics, statistics_content(stats_)); });
  const uint64_t summary_offset_start = summary_start + summary.bytes().size();

  Encoder footer;
  footer.u8(static_cast<uint8_t>(Opcode::kFooter));
  footer.u64(kFooterContent);
  footer.u64(summary_start);
  footer.u64(summary_offset_start);
  // The summary CRC covers the summary and summary-offset sections and the Footer up to the CRC.
  uint32_t summary_crc = crc32(summary.bytes());
  summary_crc = crc32(offsets.bytes(), summary_crc);
  summary_crc = crc32(footer.bytes(), summary_crc);
  footer.u32(summary_crc);

  SLAM_TRY(emit(summary.bytes(), false));
  SLAM_TRY(emit(offsets.bytes(), false));
  SLAM_TRY(emit(footer.bytes(), false));
  SLAM_TRY(emit(kMagic, false));
  closed_ = true;
  const bool flushed = std::fflush(file_) == 0;
  const bool ok = std::fclose(file_) == 0 && flushed;
  file_ = nullptr;
  if (!ok) return Error{"cannot write " + path_ + ": " + std::strerror(errno)};
  return {};
}

}  // namespace slam::mcap
