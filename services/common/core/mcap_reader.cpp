#include "common/core/mcap_reader.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "common/core/mcap_chunk.hpp"

namespace slam::mcap {
namespace {

std::string hex(uint32_t v, int digits) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%0*x", digits, v);
  return buf;
}

uint64_t le(const uint8_t* p, int n) {
  uint64_t v = 0;
  for (int i = n - 1; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}

// Reads fields from one record's content; any read past its end fails.
class Decoder {
 public:
  explicit Decoder(std::span<const uint8_t> content) : content_(content) {}
  bool u8(uint8_t& v) { return fixed(v, 1); }
  bool u16(uint16_t& v) { return fixed(v, 2); }
  bool u32(uint32_t& v) { return fixed(v, 4); }
  bool u64(uint64_t& v) { return fixed(v, 8); }
  bool bytes(std::span<const uint8_t>& out, uint64_t n) {
    if (n > content_.size() - at_) return false;
    out = content_.subspan(at_, n);
    at_ += n;
    return true;
  }
  bool prefixed(std::string& s) {
    uint32_t n = 0;
    std::span<const uint8_t> b;
    if (!u32(n) || !bytes(b, n)) return false;
    s.assign(reinterpret_cast<const char*>(b.data()), b.size());
    return true;
  }
  bool string_map(std::map<std::string, std::string>& m) {
    uint32_t n = 0;
    std::span<const uint8_t> b;
    if (!u32(n) || !bytes(b, n)) return false;
    Decoder entries(b);
    while (!entries.done()) {
      std::string key, value;
      if (!entries.prefixed(key) || !entries.prefixed(value)) return false;
      if (!m.emplace(std::move(key), std::move(value)).second) return false;
    }
    return true;
  }
  bool counts_map(std::map<uint16_t, uint64_t>& m) {
    uint32_t n = 0;
    std::span<const uint8_t> b;
    if (!u32(n) || !bytes(b, n)) return false;
    Decoder entries(b);
    while (!entries.done()) {
      uint16_t key = 0;
      uint64_t value = 0;
      if (!entries.u16(key) || !entries.u64(value) || !m.emplace(key, value).second) return false;
    }
    return true;
  }
  std::span<const uint8_t> rest() const { return content_.subspan(at_); }
  bool done() const { return at_ == content_.size(); }

 private:
  template <class T>
  bool fixed(T& v, int n) {
    if (content_.size() - at_ < static_cast<size_t>(n)) return false;
    v = static_cast<T>(le(content_.data() + at_, n));
    at_ += n;
    return true;
  }
  std::span<const uint8_t> content_;
  size_t at_ = 0;
};

const char* opcode_name(uint8_t op) {
  switch (static_cast<Opcode>(op)) {
    case Opcode::kHeader:
      return "Header";
    case Opcode::kFooter:
      return "Footer";
    case Opcode::kSchema:
      return "Schema";
    case Opcode::kChannel:
      return "Channel";
    case Opcode::kMessage:
      return "Message";
    case Opcode::kChunk:
      return "Chunk";
    case Opcode::kMessageIndex:
      return "MessageIndex";
    case Opcode::kChunkIndex:
      return "ChunkIndex";
    case Opcode::kAttachment:
      return "Attachment";
    case Opcode::kAttachmentIndex:
      return "AttachmentIndex";
    case Opcode::kStatistics:
      return "Statistics";
    case Opcode::kMetadata:
      return "Metadata";
    case Opcode::kMetadataIndex:
      return "MetadataIndex";
    case Opcode::kSummaryOffset:
      return "SummaryOffset";
    case Opcode::kDataEnd:
      return "DataEnd";
  }
  return "unknown";
}

// Parses one file; each failure names the byte offset of the record at fault.
class Parser {
 public:
  explicit Parser(std::span<const uint8_t> file) : file_(file) {}

  Result<Contents> run() {
    if (file_.size() < kMagic.size() || !std::equal(kMagic.begin(), kMagic.end(), file_.begin()))
      return Error{"not an MCAP file: no MCAP magic at the start"};
    if (file_.size() < 2 * kMagic.size() ||
        !std::equal(kMagic.begin(), kMagic.end(), file_.end() - kMagic.size()))
      return Error{"truncated MCAP file (" + std::to_string(file_.size()) +
                   " bytes): no MCAP magic at the end (was the recording not closed?)"};
    const size_t end = file_.size() - kMagic.size();
    size_t at = kMagic.size();
    while (at < end) {
      if (phase_ == Phase::kDone) return fail(at, "bytes after the Footer");
      if (end - at < kRecordPrefix) return fail(at, "truncated record prefix");
      const uint8_t op = file_[at];
      const uint64_t length = le(file_.data() + at + 1, 8);
      if (length > end - at - kRecordPrefix)
        return fail(at, std::string(opcode_name(op)) + " record (" + hex(op, 2) + ") claims " +
                            std::to_string(length) + " bytes, only " +
                            std::to_string(end - at - kRecordPrefix) + " left");
      SLAM_TRY(record(at, op, file_.subspan(at + kRecordPrefix, length)));
      at += kRecordPrefix + length;
    }
    if (phase_ != Phase::kDone)
      return Error{phase_ == Phase::kData || phase_ == Phase::kHeader
                       ? "truncated MCAP file: no DataEnd record"
                       : "truncated MCAP file: no Footer record"};
    SLAM_TRY(check_statistics());
    return std::move(out_);
  }

 private:
  enum class Phase { kHeader, kData, kSummary, kDone };

  static Error fail(size_t at, const std::string& what) {
    return Error{"MCAP byte " + std::to_string(at) + ": " + what};
  }
  static Error malformed(size_t at, uint8_t op) {
    return fail(at, std::string("malformed ") + opcode_name(op) + " record (fields run past its end)");
  }

  Status record(size_t at, uint8_t op, std::span<const uint8_t> content) {
    if (phase_ == Phase::kHeader && op != static_cast<uint8_t>(Opcode::kHeader))
      return fail(at, "the first record must be a Header, found " + std::string(opcode_name(op)) + " (" +
                          hex(op, 2) + ")");
    if (phase_ == Phase::kSummary && op != static_cast<uint8_t>(Opcode::kFooter)) {
      if (summary_first_ == 0) summary_first_ = at;
      if (op == static_cast<uint8_t>(Opcode::kSummaryOffset)) {
        if (summary_offset_first_ == 0) summary_offset_first_ = at;
      } else if (summary_offset_first_ != 0) {
        return fail(at, std::string(opcode_name(op)) + " record after the SummaryOffset records");
      }
    }
    Decoder d(content);
    switch (static_cast<Opcode>(op)) {
      case Opcode::kHeader:
        if (phase_ != Phase::kHeader) return fail(at, "a second Header record");
        if (!d.prefixed(out_.profile) || !d.prefixed(out_.library)) return malformed(at, op);
        phase_ = Phase::kData;
        return {};
      case Opcode::kSchema:
        return schema(at, op, d);
      case Opcode::kChannel:
        return channel(at, op, d);
      case Opcode::kMessage:
        return message(at, op, d);
      case Opcode::kChunk:
        return chunk(at, op, d);
      case Opcode::kStatistics:
        return statistics(at, op, d);
      case Opcode::kSummaryOffset:
        return summary_offset(at, op, d);
      case Opcode::kDataEnd:
        return data_end(at, op, d);
      case Opcode::kFooter:
        return footer(at, op, d);
      default:
        // Indexes, attachments, metadata and opcodes from newer writers: not needed here.
        ++out_.skipped_records;
        return {};
    }
  }

  Status schema(size_t at, uint8_t op, Decoder& d) {
    Schema s;
    std::span<const uint8_t> data;
    uint32_t n = 0;
    if (!d.u16(s.id) || !d.prefixed(s.name) || !d.prefixed(s.encoding) || !d.u32(n) || !d.bytes(data, n))
      return malformed(at, op);
    s.data.assign(reinterpret_cast<const char*>(data.data()), data.size());
    if (s.id == 0) return fail(at, "Schema with the reserved id 0");
    return define(at, out_.schemas, s.id, std::move(s), "Schema");
  }

  Status channel(size_t at, uint8_t op, Decoder& d) {
    Channel c;
    if (!d.u16(c.id) || !d.u16(c.schema_id) || !d.prefixed(c.topic) || !d.prefixed(c.message_encoding) ||
        !d.string_map(c.metadata))
      return malformed(at, op);
    if (c.schema_id != 0 && !out_.schemas.contains(c.schema_id))
      return fail(at,
                  "Channel " + std::to_string(c.id) + " names unknown schema " + std::to_string(c.schema_id));
    return define(at, out_.channels, c.id, std::move(c), "Channel");
  }

  // A Schema or Channel may be repeated (e.g. in the summary) but never redefined.
  template <class T>
  Status define(size_t at, std::map<uint16_t, T>& known, uint16_t id, T value, const char* kind) {
    auto it = known.find(id);
    if (it == known.end()) {
      known.emplace(id, std::move(value));
      return {};
    }
    if (!(it->second == value))
      return fail(at, std::string(kind) + " " + std::to_string(id) + " redefined with different content");
    return {};
  }

  Status message(size_t at, uint8_t op, Decoder& d) {
    if (phase_ != Phase::kData) return fail(at, "Message record outside the data section");
    MessageView m;
    if (!d.u16(m.channel_id) || !d.u32(m.sequence) || !d.u64(m.log_time) || !d.u64(m.publish_time))
      return malformed(at, op);
    if (!out_.channels.contains(m.channel_id))
      return fail(at, "Message on unknown channel " + std::to_string(m.channel_id));
    m.data = d.rest();
    out_.messages.push_back(m);
    ++counts_[m.channel_id];
    return {};
  }

  // A Chunk's records are Schema, Channel and Message records; errors inside name the chunk's offset.
  Status chunk(size_t at, uint8_t op, Decoder& d) {
    if (phase_ != Phase::kData) return fail(at, "Chunk record outside the data section");
    uint64_t start_time = 0, end_time = 0, size = 0, length = 0;
    uint32_t crc = 0;
    std::string compression;
    std::span<const uint8_t> stored;
    if (!d.u64(start_time) || !d.u64(end_time) || !d.u64(size) || !d.u32(crc) || !d.prefixed(compression) ||
        !d.u64(length) || !d.bytes(stored, length))
      return malformed(at, op);
    auto records = chunk_records(compression, stored, size);
    if (!records) return fail(at, records.message());
    if (crc != 0 && crc32(records->bytes) != crc)
      return fail(at, "chunk CRC mismatch: the chunk says " + hex(crc, 8) + ", its records give " +
                          hex(crc32(records->bytes), 8) + " (corrupted file)");
    if (records->storage) out_.chunk_storage.push_back(records->storage);
    ++out_.chunks;
    const std::span<const uint8_t> bytes = records->bytes;
    for (size_t i = 0; i < bytes.size();) {
      if (bytes.size() - i < kRecordPrefix) return fail(at, "truncated record prefix inside the chunk");
      const uint8_t inner = bytes[i];
      const uint64_t n = le(bytes.data() + i + 1, 8);
      if (n > bytes.size() - i - kRecordPrefix)
        return fail(at, std::string(opcode_name(inner)) + " record inside the chunk claims " +
                            std::to_string(n) + " bytes, only " +
                            std::to_string(bytes.size() - i - kRecordPrefix) + " left");
      Decoder content(bytes.subspan(i + kRecordPrefix, n));
      switch (static_cast<Opcode>(inner)) {
        case Opcode::kSchema:
          SLAM_TRY(schema(at, inner, content));
          break;
        case Opcode::kChannel:
          SLAM_TRY(channel(at, inner, content));
          break;
        case Opcode::kMessage:
          SLAM_TRY(message(at, inner, content));
          break;
        case Opcode::kHeader:
        case Opcode::kFooter:
        case Opcode::kChunk:
        case Opcode::kDataEnd:
        case Opcode::kStatistics:
        case Opcode::kSummaryOffset:
          return fail(at, std::string(opcode_name(inner)) + " record inside a chunk");
        default:
          ++out_.skipped_records;
      }
      i += kRecordPrefix + n;
    }
    return {};
  }

  Status statistics(size_t at, uint8_t op, Decoder& d) {
    if (phase_ != Phase::kSummary) return fail(at, "Statistics record outside the summary section");
    if (out_.statistics) return fail(at, "a second Statistics record");
    Statistics s;
    if (!d.u64(s.message_count) || !d.u16(s.schema_count) || !d.u32(s.channel_count) ||
        !d.u32(s.attachment_count) || !d.u32(s.metadata_count) || !d.u32(s.chunk_count) ||
        !d.u64(s.message_start_time) || !d.u64(s.message_end_time) || !d.counts_map(s.channel_message_counts))
      return malformed(at, op);
    out_.statistics = std::move(s);
    return {};
  }

  Status summary_offset(size_t at, uint8_t op, Decoder& d) {
    if (phase_ != Phase::kSummary) return fail(at, "SummaryOffset record outside the summary");
    uint8_t group = 0;
    uint64_t start = 0, length = 0;
    if (!d.u8(group) || !d.u64(start) || !d.u64(length)) return malformed(at, op);
    // The group must lie in the summary section, before the SummaryOffset records.
    if (start < summary_first_ || start > at || length > at - start)
      return fail(at, std::string("SummaryOffset of the ") + opcode_name(group) +
                          " group points outside the summary section");
    return {};
  }

  Status data_end(size_t at, uint8_t op, Decoder& d) {
    if (phase_ != Phase::kData) return fail(at, "a second DataEnd record");
    uint32_t crc = 0;
    if (!d.u32(crc)) return malformed(at, op);
    // The data section: every byte before DataEnd, leading magic included. 0 means "not computed".
    if (crc != 0) {
      const uint32_t actual = crc32(file_.first(at));
      if (actual != crc)
        return fail(at, "data section CRC mismatch: DataEnd says " + hex(crc, 8) + ", the bytes give " +
                            hex(actual, 8) + " (corrupted file)");
    }
    phase_ = Phase::kSummary;
    return {};
  }

  Status footer(size_t at, uint8_t op, Decoder& d) {
    if (phase_ != Phase::kSummary) return fail(at, "Footer before the DataEnd record");
    uint64_t summary_start = 0, summary_offset_start = 0;
    uint32_t crc = 0;
    if (!d.u64(summary_start) || !d.u64(summary_offset_start) || !d.u32(crc)) return malformed(at, op);
    if (summary_start != summary_first_)
      return fail(at, "Footer says the summary starts at byte " + std::to_string(summary_start) +
                          ", it starts at " + std::to_string(summary_first_));
    if (summary_offset_start != 0 && summary_offset_start != summary_offset_first_)
      return fail(at, "Footer says the summary offsets start at byte " +
                          std::to_string(summary_offset_start) + ", they start at " +
                          std::to_string(summary_offset_first_));
    if (crc != 0) {
      // From the summary start (or the Footer, without a summary) to the Footer's CRC field.
      const size_t from = summary_start != 0 ? summary_start : at;
      const size_t to = at + kRecordPrefix + 16;
      const uint32_t actual = crc32(file_.subspan(from, to - from));
      if (actual != crc)
        return fail(at, "summary CRC mismatch: Footer says " + hex(crc, 8) + ", the bytes give " +
                            hex(actual, 8) + " (corrupted file)");
    }
    phase_ = Phase::kDone;
    return {};
  }

  Status check_statistics() const {
    if (!out_.statistics) return {};
    const Statistics& s = *out_.statistics;
    if (s.message_count != out_.messages.size())
      return Error{"MCAP Statistics say " + std::to_string(s.message_count) + " messages, the file has " +
                   std::to_string(out_.messages.size())};
    if (s.schema_count != out_.schemas.size() || s.channel_count != out_.channels.size())
      return Error{"MCAP Statistics count " + std::to_string(s.schema_count) + " schemas and " +
                   std::to_string(s.channel_count) + " channels, the file has " +
                   std::to_string(out_.schemas.size()) + " and " + std::to_string(out_.channels.size())};
    for (const auto& [channel, n] : s.channel_message_counts) {
      auto it = counts_.find(channel);
      if ((it == counts_.end() ? 0 : it->second) != n)
        return Error{"MCAP Statistics count " + std::to_string(n) + " messages on channel " +
                     std::to_string(channel) + ", the file has " +
                     std::to_string(it == counts_.end() ? 0 : it->second)};
    }
    return {};
  }

  std::span<const uint8_t> file_;
  Phase phase_ = Phase::kHeader;
  size_t summary_first_ = 0;         // offset of the first summary record, 0 without one
  size_t summary_offset_first_ = 0;  // offset of the first SummaryOffset record, 0 without one
  std::map<uint16_t, uint64_t> counts_;
  Contents out_;
};

}  // namespace

Result<Contents> parse(std::span<const uint8_t> file) {
  return Parser(file).run();
}

Result<std::unique_ptr<MappedFile>> MappedFile::open(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return Error{"cannot open " + path + ": " + std::strerror(errno)};
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    const int err = errno;
    ::close(fd);
    return Error{"cannot stat " + path + ": " + std::strerror(err)};
  }
  const auto size = static_cast<size_t>(st.st_size);
  if (size == 0) {
    ::close(fd);
    return std::unique_ptr<MappedFile>(new MappedFile(nullptr, 0));
  }
  void* data = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0);
  const int err = errno;
  ::close(fd);
  if (data == MAP_FAILED) return Error{"cannot map " + path + ": " + std::strerror(err)};
  return std::unique_ptr<MappedFile>(new MappedFile(static_cast<const uint8_t*>(data), size));
}

MappedFile::~MappedFile() {
  if (data_) ::munmap(const_cast<uint8_t*>(data_), size_);
}

}  // namespace slam::mcap
