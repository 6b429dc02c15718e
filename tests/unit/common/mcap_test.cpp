// The MCAP writer and reader: round trip, CRCs, truncation, records the reader does not use.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "common/core/mcap_reader.hpp"
#include "common/core/mcap_writer.hpp"
#include "temp_dir.hpp"

namespace slam::mcap {
namespace {

std::vector<uint8_t> file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::span<const uint8_t> as_bytes(std::string_view s) {
  return {reinterpret_cast<const uint8_t*>(s.data()), s.size()};
}

std::string as_string(std::span<const uint8_t> b) {
  return {reinterpret_cast<const char*>(b.data()), b.size()};
}

// Two schemas, three channels (one without schema), five messages; closed.
std::vector<uint8_t> sample_recording(const testkit::TempDir& dir) {
  auto writer = Writer::create((dir / "sample.mcap").string(), "mcap_test");
  EXPECT_TRUE(writer) << writer.message();
  auto state = (*writer)->add_schema("slam::RobotState", "omgidl", "struct RobotState { long x; };");
  auto beat = (*writer)->add_schema("slam::Heartbeat", "omgidl", "struct Heartbeat { long y; };");
  EXPECT_TRUE(state && beat);
  auto a = (*writer)->add_channel(*state, "slam/robot/state", "cdr", {{"qos", "state"}});
  auto b = (*writer)->add_channel(*beat, "slam/system/heartbeat", "cdr");
  auto c = (*writer)->add_channel(0, "raw", "octets");
  EXPECT_TRUE(a && b && c);
  EXPECT_TRUE((*writer)->write_message(*a, 100, 90, as_bytes("first")));
  EXPECT_TRUE((*writer)->write_message(*b, 110, 0, as_bytes("beat")));
  EXPECT_TRUE((*writer)->write_message(*a, 120, 115, as_bytes("second")));
  EXPECT_TRUE((*writer)->write_message(*c, 130, 130, {}));
  EXPECT_TRUE((*writer)->write_message(*a, 105, 100, as_bytes("late")));
  EXPECT_EQ((*writer)->message_count(), 5u);
  EXPECT_TRUE((*writer)->close());
  return file_bytes(dir / "sample.mcap");
}

TEST(McapReader, ReadsBackWhatTheWriterWrote) {
  testkit::TempDir dir("mcap");
  const std::vector<uint8_t> bytes = sample_recording(dir);
  auto contents = parse(bytes);
  ASSERT_TRUE(contents) << contents.message();
  EXPECT_EQ(contents->library, "mcap_test");
  EXPECT_EQ(contents->profile, "");
  ASSERT_EQ(contents->schemas.size(), 2u);
  EXPECT_EQ(contents->schemas.at(1).name, "slam::RobotState");
  EXPECT_EQ(contents->schemas.at(1).encoding, "omgidl");
  EXPECT_EQ(contents->schemas.at(2).data, "struct Heartbeat { long y; };");
  ASSERT_EQ(contents->channels.size(), 3u);
  EXPECT_EQ(contents->channels.at(1).topic, "slam/robot/state");
  EXPECT_EQ(contents->channels.at(1).schema_id, 1);
  EXPECT_EQ(contents->channels.at(1).metadata.at("qos"), "state");
  EXPECT_EQ(contents->channels.at(3).schema_id, 0);
  EXPECT_EQ(contents->channels.at(3).message_encoding, "octets");

  ASSERT_EQ(contents->messages.size(), 5u);
  const MessageView& late = contents->messages[4];
  EXPECT_EQ(late.channel_id, 1);
  EXPECT_EQ(late.sequence, 3u);  // third message on its channel
  EXPECT_EQ(late.log_time, 105u);
  EXPECT_EQ(late.publish_time, 100u);
  EXPECT_EQ(as_string(late.data), "late");
  EXPECT_EQ(as_string(contents->messages[1].data), "beat");
  EXPECT_TRUE(contents->messages[3].data.empty());

  ASSERT_TRUE(contents->statistics);
  EXPECT_EQ(contents->statistics->message_count, 5u);
  EXPECT_EQ(contents->statistics->schema_count, 2);
  EXPECT_EQ(contents->statistics->channel_count, 3u);
  EXPECT_EQ(contents->statistics->message_start_time, 100u);
  EXPECT_EQ(contents->statistics->message_end_time, 130u);
  EXPECT_EQ(contents->statistics->channel_message_counts,
            (std::map<uint16_t, uint64_t>{{1, 3}, {2, 1}, {3, 1}}));
  EXPECT_EQ(contents->skipped_records, 0u);
}

TEST(McapReader, ReadsAnEmptyRecording) {
  testkit::TempDir dir("mcap");
  auto writer = Writer::create((dir / "empty.mcap").string(), "mcap_test");
  ASSERT_TRUE(writer);
  ASSERT_TRUE((*writer)->close());
  auto contents = parse(file_bytes(dir / "empty.mcap"));
  ASSERT_TRUE(contents) << contents.message();
  EXPECT_TRUE(contents->messages.empty());
  EXPECT_EQ(contents->statistics->message_count, 0u);
}

TEST(McapReader, DetectsACorruptedMessageByTheDataCrc) {
  testkit::TempDir dir("mcap");
  std::vector<uint8_t> bytes = sample_recording(dir);
  const std::string needle = "second";
  auto at = std::search(bytes.begin(), bytes.end(), needle.begin(), needle.end());
  ASSERT_NE(at, bytes.end());
  *at ^= 0x20;
  auto contents = parse(bytes);
  ASSERT_FALSE(contents);
  EXPECT_NE(contents.message().find("data section CRC mismatch"), std::string::npos) << contents.message();
}

TEST(McapReader, DetectsACorruptedSummaryByTheSummaryCrc) {
  testkit::TempDir dir("mcap");
  std::vector<uint8_t> bytes = sample_recording(dir);
  // The Footer's summary_offset_start; the byte before it ends the Statistics record.
  const size_t footer = bytes.size() - kMagic.size() - kRecordPrefix - kFooterContent;
  uint64_t summary_offset_start = 0;
  for (int i = 7; i >= 0; --i) summary_offset_start = (summary_offset_start << 8) | bytes[footer + 17 + i];
  ASSERT_LT(summary_offset_start, footer);
  bytes[summary_offset_start - 1] ^= 0x01;
  auto contents = parse(bytes);
  ASSERT_FALSE(contents);
  EXPECT_NE(contents.message().find("summary CRC mismatch"), std::string::npos) << contents.message();
}

TEST(McapReader, RefusesEveryTruncationOfAFile) {
  testkit::TempDir dir("mcap");
  const std::vector<uint8_t> bytes = sample_recording(dir);
  for (size_t n = 0; n < bytes.size(); ++n) {
    auto contents = parse(std::span<const uint8_t>(bytes).first(n));
    EXPECT_FALSE(contents) << "cut to " << n << " bytes";
  }
  auto cut = parse(std::span<const uint8_t>(bytes).first(bytes.size() - 1));
  EXPECT_NE(cut.message().find("truncated"), std::string::npos) << cut.message();
}

TEST(McapReader, RefusesAFileWithoutTheMagic) {
  const std::string text = "just some text, long enough to be mistaken for a file";
  auto contents = parse(as_bytes(text));
  ASSERT_FALSE(contents);
  EXPECT_NE(contents.message().find("not an MCAP file"), std::string::npos);
}

// A hand-made file: magic, Header, then `data` records, DataEnd without CRC, a Footer without
// summary, magic.
std::vector<uint8_t> hand_made(const std::function<void(Encoder&)>& data) {
  Encoder file;
  file.raw(kMagic);
  Encoder header;
  header.prefixed("");
  header.prefixed("hand");
  file.record(Opcode::kHeader, header.bytes());
  data(file);
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

void add_channel_and_message(Encoder& file, uint16_t channel_of_message) {
  Encoder channel;
  channel.u16(7);
  channel.u16(0);
  channel.prefixed("topic");
  channel.prefixed("json");
  channel.string_map({});
  file.record(Opcode::kChannel, channel.bytes());
  Encoder message;
  message.u16(channel_of_message);
  message.u32(1);
  message.u64(5);
  message.u64(5);
  message.raw(as_bytes("{}"));
  file.record(Opcode::kMessage, message.bytes());
}

TEST(McapReader, SkipsRecordsItDoesNotUse) {
  const auto bytes = hand_made([](Encoder& file) {
    const std::vector<uint8_t> opaque{1, 2, 3};
    file.record(static_cast<Opcode>(0x80), opaque);  // user-defined opcode
    Encoder metadata;
    metadata.prefixed("site");
    metadata.string_map({{"room", "lab"}});
    file.record(Opcode::kMetadata, metadata.bytes());
    add_channel_and_message(file, 7);
    file.record(static_cast<Opcode>(0x42), {});  // an opcode of a newer specification
  });
  auto contents = parse(bytes);
  ASSERT_TRUE(contents) << contents.message();
  EXPECT_EQ(contents->skipped_records, 3u);
  ASSERT_EQ(contents->messages.size(), 1u);
  EXPECT_EQ(as_string(contents->messages[0].data), "{}");
  EXPECT_FALSE(contents->statistics);
}

TEST(McapReader, RefusesAMessageOnAnUnknownChannel) {
  auto contents = parse(hand_made([](Encoder& file) { add_channel_and_message(file, 8); }));
  ASSERT_FALSE(contents);
  EXPECT_NE(contents.message().find("unknown channel 8"), std::string::npos) << contents.message();
}

TEST(McapReader, RefusesARecordLongerThanTheFile) {
  auto contents = parse(hand_made([](Encoder& file) {
    file.u8(static_cast<uint8_t>(Opcode::kSchema));
    file.u64(uint64_t{1} << 40);
  }));
  ASSERT_FALSE(contents);
  EXPECT_NE(contents.message().find("claims"), std::string::npos) << contents.message();
}

TEST(McapReader, RefusesARecordWhoseFieldsRunPastItsEnd) {
  auto contents = parse(hand_made([](Encoder& file) {
    Encoder schema;
    schema.u16(1);
    schema.u32(1000);  // name length beyond the record
    file.record(Opcode::kSchema, schema.bytes());
  }));
  ASSERT_FALSE(contents);
  EXPECT_NE(contents.message().find("malformed Schema"), std::string::npos) << contents.message();
}

TEST(McapWriter, RefusesUnknownIds) {
  testkit::TempDir dir("mcap");
  auto writer = Writer::create((dir / "ids.mcap").string(), "mcap_test");
  ASSERT_TRUE(writer);
  EXPECT_FALSE((*writer)->add_channel(3, "t", "cdr"));
  EXPECT_FALSE((*writer)->write_message(1, 0, 0, {}));
}

TEST(McapWriter, ReportsAFileItCannotCreate) {
  auto writer = Writer::create("/nonexistent-dir/x.mcap", "mcap_test");
  ASSERT_FALSE(writer);
  EXPECT_NE(writer.message().find("/nonexistent-dir/x.mcap"), std::string::npos);
}

}  // namespace
}  // namespace slam::mcap
