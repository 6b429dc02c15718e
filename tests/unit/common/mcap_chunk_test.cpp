// MCAP chunks, as other writers make them: uncompressed, zstd and lz4 chunks read like unchunked
// records, and broken chunks (CRC, sizes, nested records, unknown compression) refused by offset.
#include "common/core/mcap_chunk.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "common/core/mcap_reader.hpp"

#ifdef SLAM_HAVE_ZSTD
#include <zstd.h>
#endif
#ifdef SLAM_HAVE_LZ4
#include <lz4frame.h>
#endif

namespace slam::mcap {
namespace {

// A Schema, a Channel on it and two Messages, as the records inside a chunk.
std::vector<uint8_t> chunk_contents() {
  Encoder records;
  Encoder schema;
  schema.u16(1);
  schema.prefixed("std_msgs/msg/String");
  schema.prefixed("ros2msg");
  schema.prefixed("string data");
  records.record(Opcode::kSchema, schema.bytes());
  Encoder channel;
  channel.u16(3);
  channel.u16(1);
  channel.prefixed("/chatter");
  channel.prefixed("cdr");
  channel.string_map({});
  records.record(Opcode::kChannel, channel.bytes());
  for (uint8_t i = 0; i < 2; ++i) {
    Encoder message;
    message.u16(3);
    message.u32(i);
    message.u64(100 + i);
    message.u64(100 + i);
    message.raw(std::vector<uint8_t>{'m', static_cast<uint8_t>('0' + i)});
    records.record(Opcode::kMessage, message.bytes());
  }
  return records.bytes();
}

// A whole file with one chunk holding `stored` (records compressed with `compression`).
std::vector<uint8_t> chunked_file(std::string_view compression, const std::vector<uint8_t>& stored,
                                  uint64_t uncompressed_size, uint32_t crc) {
  Encoder file;
  file.raw(kMagic);
  Encoder header;
  header.prefixed("ros2");
  header.prefixed("chunk test");
  file.record(Opcode::kHeader, header.bytes());
  Encoder chunk;
  chunk.u64(100);
  chunk.u64(101);
  chunk.u64(uncompressed_size);
  chunk.u32(crc);
  chunk.prefixed(compression);
  chunk.u64(stored.size());
  chunk.raw(stored);
  file.record(Opcode::kChunk, chunk.bytes());
  Encoder data_end;
  data_end.u32(0);
  file.record(Opcode::kDataEnd, data_end.bytes());
  Encoder footer;
  footer.u64(0);
  footer.u64(0);
  footer.u32(0);
  file.record(Opcode::kFooter, footer.bytes());
  file.raw(kMagic);
  return file.bytes();
}

void expect_two_messages(const Result<Contents>& contents) {
  ASSERT_TRUE(contents) << contents.message();
  EXPECT_EQ(contents->chunks, 1u);
  ASSERT_EQ(contents->messages.size(), 2u);
  EXPECT_EQ(contents->channels.at(3).topic, "/chatter");
  EXPECT_EQ(contents->schemas.at(1).encoding, "ros2msg");
  EXPECT_EQ(contents->messages[1].log_time, 101u);
  EXPECT_EQ(std::string(contents->messages[1].data.begin(), contents->messages[1].data.end()), "m1");
}

TEST(McapChunk, UncompressedChunkIsRead) {
  const auto records = chunk_contents();
  const auto file = chunked_file("", records, records.size(), crc32(records));
  expect_two_messages(parse(file));
  EXPECT_TRUE(parse(file)->chunk_storage.empty());  // messages point into the file itself
}

TEST(McapChunk, BrokenChunksAreRefused) {
  const auto records = chunk_contents();
  const auto refused = [](const std::vector<uint8_t>& file) {
    auto contents = parse(file);
    return contents ? std::string("parsed") : contents.message();
  };
  EXPECT_NE(refused(chunked_file("", records, records.size(), crc32(records) + 1)).find("chunk CRC mismatch"),
            std::string::npos);
  EXPECT_NE(refused(chunked_file("", records, records.size() + 1, 0)).find("header says"), std::string::npos);
  EXPECT_NE(refused(chunked_file("brotli", records, records.size(), 0)).find("unknown chunk compression"),
            std::string::npos);
  EXPECT_NE(refused(chunked_file("zstd", records, kMaxChunkBytes + 1, 0)).find("more than"),
            std::string::npos);
  auto cut = records;
  cut.pop_back();
  EXPECT_NE(refused(chunked_file("", cut, cut.size(), 0)).find("inside the chunk"), std::string::npos);
  Encoder nested;
  nested.record(Opcode::kDataEnd, std::vector<uint8_t>(4));
  EXPECT_NE(refused(chunked_file("", nested.bytes(), nested.bytes().size(), 0))
                .find("DataEnd record inside a chunk"),
            std::string::npos);
}

#ifdef SLAM_HAVE_ZSTD
TEST(McapChunk, ZstdChunkIsRead) {
  const auto records = chunk_contents();
  std::vector<uint8_t> packed(ZSTD_compressBound(records.size()));
  packed.resize(ZSTD_compress(packed.data(), packed.size(), records.data(), records.size(), 3));
  const auto contents = parse(chunked_file("zstd", packed, records.size(), crc32(records)));
  expect_two_messages(contents);
  EXPECT_EQ(contents->chunk_storage.size(), 1u);
  packed.resize(packed.size() / 2);
  EXPECT_FALSE(parse(chunked_file("zstd", packed, records.size(), 0)));
}
#endif

#ifdef SLAM_HAVE_LZ4
TEST(McapChunk, Lz4ChunkIsRead) {
  const auto records = chunk_contents();
  std::vector<uint8_t> packed(LZ4F_compressFrameBound(records.size(), nullptr));
  packed.resize(LZ4F_compressFrame(packed.data(), packed.size(), records.data(), records.size(), nullptr));
  expect_two_messages(parse(chunked_file("lz4", packed, records.size(), crc32(records))));
  EXPECT_FALSE(parse(chunked_file("lz4", packed, records.size() + 5, 0)));
  packed.resize(packed.size() - 6);
  EXPECT_FALSE(parse(chunked_file("lz4", packed, records.size(), 0)));
}
#endif

}  // namespace
}  // namespace slam::mcap
