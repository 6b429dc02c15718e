// The file side of slamctl record / replay: the recorder's MCAP output, --topics, the replay plan
// and its timing.
#include "slamctl/recording.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <thread>

#include "temp_dir.hpp"

namespace slam::ctl {
namespace {

std::vector<uint8_t> file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

const std::vector<uint8_t> kCdr{0, 1, 0, 0, 42, 0, 0, 0};

TEST(SessionRecorder, WritesOneChannelAndOmgidlSchemaPerTopic) {
  testkit::TempDir dir("recording");
  auto recorder = SessionRecorder::create((dir / "r.mcap").string());
  ASSERT_TRUE(recorder) << recorder.message();
  (*recorder)->add("slam/robot/state", "slam::RobotState", kCdr, 10, 9);
  (*recorder)->add("slam/system/heartbeat", "slam::Heartbeat", kCdr, 11, 10);
  (*recorder)->add("slam/robot/state", "slam::RobotState", kCdr, 12, 11);
  EXPECT_EQ((*recorder)->stats().messages, 3u);
  EXPECT_EQ((*recorder)->stats().topics, 2u);
  ASSERT_TRUE((*recorder)->close());

  const auto bytes = file_bytes(dir / "r.mcap");
  auto contents = mcap::parse(bytes);
  ASSERT_TRUE(contents) << contents.message();
  ASSERT_EQ(contents->channels.size(), 2u);
  for (const auto& [id, channel] : contents->channels) {
    EXPECT_EQ(channel.message_encoding, "cdr");
    const mcap::Schema& schema = contents->schemas.at(channel.schema_id);
    EXPECT_EQ(schema.encoding, "omgidl");
    EXPECT_EQ(schema.name, channel.topic == "slam/robot/state" ? "slam::RobotState" : "slam::Heartbeat");
    EXPECT_NE(
        schema.data.find(channel.topic == "slam/robot/state" ? "struct RobotState" : "struct Heartbeat"),
        std::string::npos);
  }
  ASSERT_EQ(contents->messages.size(), 3u);
  EXPECT_EQ(std::vector<uint8_t>(contents->messages[2].data.begin(), contents->messages[2].data.end()), kCdr);
  EXPECT_EQ(contents->messages[2].log_time, 12u);
  EXPECT_EQ(contents->messages[2].publish_time, 11u);
}

TEST(SessionRecorder, TakesSamplesFromSeveralThreads) {
  testkit::TempDir dir("recording");
  auto recorder = SessionRecorder::create((dir / "r.mcap").string());
  ASSERT_TRUE(recorder);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      for (int i = 0; i < 100; ++i)
        (*recorder)->add(t % 2 ? "slam/robot/state" : "slam/system/heartbeat",
                         t % 2 ? "slam::RobotState" : "slam::Heartbeat", kCdr, static_cast<uint64_t>(i), 0);
    });
  for (auto& th : threads) th.join();
  ASSERT_TRUE((*recorder)->close());
  auto contents = mcap::parse(file_bytes(dir / "r.mcap"));
  ASSERT_TRUE(contents) << contents.message();
  EXPECT_EQ(contents->messages.size(), 400u);
  EXPECT_EQ(contents->channels.size(), 2u);
}

TEST(SessionRecorder, ReportsATypeWithoutIdlAtClose) {
  testkit::TempDir dir("recording");
  auto recorder = SessionRecorder::create((dir / "r.mcap").string());
  ASSERT_TRUE(recorder);
  (*recorder)->add("slam/x", "slam::NoSuchType", kCdr, 1, 1);
  EXPECT_TRUE((*recorder)->failed());
  const Status closed = (*recorder)->close();
  ASSERT_FALSE(closed);
  EXPECT_NE(closed.message().find("slam::NoSuchType"), std::string::npos);
  EXPECT_TRUE(mcap::parse(file_bytes(dir / "r.mcap"))) << "the file is still ended";
}

TEST(SelectTopics, SplitsTheCommaListAllWhenEmptyAndRefusesUnknownNames) {
  const std::vector<std::string> all{"a", "b", "c"};
  EXPECT_EQ(*select_topics("", all), all);
  EXPECT_EQ(*select_topics("c,a", all), (std::vector<std::string>{"c", "a"}));
  EXPECT_EQ(*select_topics("b", all), (std::vector<std::string>{"b"}));
  auto unknown = select_topics("a,zz", all);
  ASSERT_FALSE(unknown);
  EXPECT_NE(unknown.message().find("'zz'"), std::string::npos);
  EXPECT_FALSE(select_topics(",", all));
}

mcap::Contents recording_with(
    std::vector<std::tuple<uint16_t, std::string, std::string, std::string>> channels) {
  mcap::Contents c;
  uint16_t schema_id = 0;
  for (auto& [id, topic, encoding, type] : channels) {
    ++schema_id;
    c.schemas[schema_id] = mcap::Schema{schema_id, type, "omgidl", "idl"};
    c.channels[id] = mcap::Channel{id, schema_id, topic, encoding, {}};
  }
  return c;
}

TEST(PlanReplay, ReplaysKnownTopicsOfTheRightTypeAndSaysWhyOthersAreSkipped) {
  const std::map<std::string, std::string> type_of{{"slam/robot/state", "slam::RobotState"},
                                                   {"slam/system/heartbeat", "slam::Heartbeat"}};
  const auto recording = recording_with({{1, "slam/robot/state", "cdr", "slam::RobotState"},
                                         {2, "/other/robot", "cdr", "other::Thing"},
                                         {3, "slam/system/heartbeat", "cdr", "slam::OldHeartbeat"},
                                         {4, "slam/system/heartbeat", "json", "slam::Heartbeat"}});
  const ReplayPlan plan = plan_replay(recording, type_of, {});
  EXPECT_EQ(plan.topic_of, (std::map<uint16_t, std::string>{{1, "slam/robot/state"}}));
  ASSERT_EQ(plan.skipped.size(), 3u);
  EXPECT_NE(plan.skipped[0].find("not a topic of this system"), std::string::npos) << plan.skipped[0];
  EXPECT_NE(plan.skipped[1].find("slam::OldHeartbeat"), std::string::npos) << plan.skipped[1];
  EXPECT_NE(plan.skipped[2].find("not CDR"), std::string::npos) << plan.skipped[2];
}

TEST(PlanReplay, LeavesOutTopicsNotSelectedWithoutALine) {
  const std::map<std::string, std::string> type_of{{"slam/robot/state", "slam::RobotState"},
                                                   {"slam/system/heartbeat", "slam::Heartbeat"}};
  const auto recording = recording_with({{1, "slam/robot/state", "cdr", "slam::RobotState"},
                                         {2, "slam/system/heartbeat", "cdr", "slam::Heartbeat"}});
  const ReplayPlan plan = plan_replay(recording, type_of, {"slam/system/heartbeat"});
  EXPECT_EQ(plan.topic_of, (std::map<uint16_t, std::string>{{2, "slam/system/heartbeat"}}));
  EXPECT_TRUE(plan.skipped.empty());
}

TEST(ReplayOffset, ScalesTheRecordedDelayByTheRate) {
  using std::chrono::nanoseconds;
  EXPECT_EQ(replay_offset(1000, 1000, 1.0), nanoseconds(0));
  EXPECT_EQ(replay_offset(1000, 3000, 1.0), nanoseconds(2000));
  EXPECT_EQ(replay_offset(1000, 3000, 2.0), nanoseconds(1000));
  EXPECT_EQ(replay_offset(1000, 3000, 0.5), nanoseconds(4000));
  EXPECT_EQ(replay_offset(1000, 500, 1.0), nanoseconds(0));  // logged before the first: at once
}

}  // namespace
}  // namespace slam::ctl
