// `slamctl record` and `slamctl replay` against real DDS traffic: the test's own writers publish on
// three topics while slamctl records; the file is read back with the MCAP reader (every topic that
// had traffic has its channel and omgidl schema, and the samples' bytes decode to what was sent; and
// @mcap/core, Foxglove's own MCAP library, in Node reads it too);
// then slamctl replays the file into a fresh domain and a reader there receives the same samples.
// Generous timeouts: CI machines are loaded. No timings are asserted.
#include <gtest/gtest.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "common/core/mcap_reader.hpp"
#include "common/core/mcap_writer.hpp"
#include "common/fastdds/any_topic.hpp"
#include "fastdds_inbox.hpp"
#include "process_group.hpp"
#include "temp_dir.hpp"

namespace slam::testkit {
namespace {

constexpr auto kExitTimeout = 60s;

std::unique_ptr<dds::Participant> participant(int domain) {
  auto p = dds::Participant::create(domain, "record-replay-test");
  if (!p) throw std::runtime_error(p.message());
  return std::move(*p);
}

RobotState robot_state(int i) {
  RobotState s;
  s.robot_id("robot-" + std::to_string(i));  // one instance each: keep-last-1 keeps every sample
  s.pose().x(0.5 * i);
  s.pose().y(-1.0 * i);
  s.messages(100 + i);
  s.battery(0.25f);
  s.status("exploring");
  return s;
}

// A gateway's batch of two observations.
RobotObservationBatch observations(int i) {
  RobotObservationBatch batch;
  batch.gateway_id("host:1");
  batch.batch_seq(static_cast<uint64_t>(i) + 1);
  for (int k = 0; k < 2; ++k) {
    RobotObservation& o = batch.observations().emplace_back();
    o.robot_id("robot-" + std::to_string(k));
    o.seq(static_cast<uint64_t>(i) + 1);
    o.stamp_ns(1'000'000'000LL * i);
    Point2 hit;
    hit.x(1.0 + i);
    hit.y(2.0);
    o.hits().assign(static_cast<size_t>((i + k) % 4), hit);
  }
  return batch;
}

Heartbeat heartbeat(int i) {
  Heartbeat h;
  h.service("test-service-" + std::to_string(i));
  h.instance_id("instance");
  h.pid(4242);
  h.state(SERVICE_RUNNING);
  Counter c;
  c.name("samples");
  c.value(i);
  h.counters().push_back(c);
  return h;
}

constexpr int kStates = 4;
constexpr int kObservations = 12;
constexpr int kHeartbeats = 2;

// Writes each sample once its reader matched, waiting for its acknowledgement (no sample replaced
// in a writer's history before it was delivered).
template <class T>
void publish_all(dds::Writer<T>& writer, const std::vector<T>& samples) {
  ASSERT_TRUE(writer.wait_for_readers(30s)) << writer.topic_name() << ": slamctl record never subscribed";
  for (const T& s : samples) {
    ASSERT_TRUE(writer.write(s));
    ASSERT_TRUE(writer.wait_for_acknowledgments(10s));
  }
}

template <class T, class F>
std::vector<T> make(int n, F f) {
  std::vector<T> out;
  for (int i = 0; i < n; ++i) out.push_back(f(i));
  return out;
}

// The messages of `topic` in the recording, decoded.
template <class P, class T>
std::vector<T> recorded(const mcap::Contents& c, const std::string& topic) {
  std::vector<T> out;
  for (const mcap::MessageView& m : c.messages) {
    if (c.channels.at(m.channel_id).topic != topic) continue;
    T sample;
    EXPECT_TRUE(dds::from_cdr<P>(m.data, sample)) << topic;
    out.push_back(sample);
  }
  return out;
}

// The recording read by @mcap/core (tests/node/mcap_reader_test.mjs), the library Foxglove reads
// MCAP with: it opens, counts and checks the CRCs, and each topic has its cdr channel and schema.
void expect_mcap_core_reads(ProcessGroup& group, const std::string& file,
                            const std::map<std::string, std::string>& schema_of) {
  if (std::system("node --version > /dev/null 2>&1") != 0) {
    std::cout << "node is not installed (apt-get install nodejs): @mcap/core check skipped\n";
    return;
  }
  const std::string node_dir = SLAM_NODE_TESTS_DIR;
  ASSERT_TRUE(std::filesystem::exists(node_dir + "/node_modules/@mcap/core"))
      << "the pinned npm packages are missing: run scripts/setup.sh (npm ci in tests/node)";
  std::vector<std::string> args = {"node", node_dir + "/mcap_reader_test.mjs", file};
  for (const auto& [topic, schema] : schema_of) args.push_back(topic + "=" + schema);
  group.start("mcap_core", args);
  EXPECT_EQ(group.wait_exit("mcap_core", kExitTimeout), 0) << group.log("mcap_core");
}

TEST(RecordReplayTest, RecordsEveryTopicWithTrafficAndReplaysItIntoAFreshDomain) {
  TempDir dir("record");
  const std::string file = (dir / "session.mcap").string();
  ProcessGroup group;
  const auto states = make<RobotState>(kStates, robot_state);
  const auto batches = make<RobotObservationBatch>(kObservations, observations);
  const auto beats = make<Heartbeat>(kHeartbeats, heartbeat);

  {
    DomainLease domain;
    auto p = participant(domain.id());
    auto state_writer = make_test_writer(*p, dds::kRobotState);
    auto observation_writer = make_test_writer(*p, dds::kRobotObservations);
    auto heartbeat_writer = make_test_writer(*p, dds::kHeartbeat);
    group.start("record", {bin_path("slamctl"), "--domain", std::to_string(domain.id()), "record", file,
                           "--duration", "10"});
    publish_all(*state_writer, states);
    publish_all(*observation_writer, batches);
    publish_all(*heartbeat_writer, beats);
    ASSERT_EQ(group.wait_exit("record", kExitTimeout), 0) << group.log("record");
    EXPECT_NE(group.log("record").find("recorded"), std::string::npos) << group.log("record");
  }

  auto mapped = mcap::MappedFile::open(file);
  ASSERT_TRUE(mapped) << mapped.message();
  auto contents = mcap::parse((*mapped)->bytes());
  ASSERT_TRUE(contents) << contents.message();
  std::map<std::string, std::string> schema_of;  // topic -> schema name
  for (const auto& [id, channel] : contents->channels) {
    EXPECT_EQ(channel.message_encoding, "cdr");
    const mcap::Schema& schema = contents->schemas.at(channel.schema_id);
    EXPECT_EQ(schema.encoding, "omgidl");
    schema_of[channel.topic] = schema.name;
    const std::string local = schema.name.substr(schema.name.rfind(':') + 1);
    EXPECT_NE(schema.data.find("struct " + local), std::string::npos) << schema.data;
  }
  // Exactly the topics that had traffic: the test's three (nothing else runs in the domain).
  EXPECT_EQ(schema_of,
            (std::map<std::string, std::string>{{"slam/robot/state", "slam::RobotState"},
                                                {"slam/robot/observations", "slam::RobotObservationBatch"},
                                                {"slam/system/heartbeat", "slam::Heartbeat"}}));
  EXPECT_EQ((recorded<RobotStatePubSubType, RobotState>(*contents, "slam/robot/state")), states);
  EXPECT_EQ((recorded<RobotObservationBatchPubSubType, RobotObservationBatch>(*contents,
                                                                              "slam/robot/observations")),
            batches);
  EXPECT_EQ((recorded<HeartbeatPubSubType, Heartbeat>(*contents, "slam/system/heartbeat")), beats);
  expect_mcap_core_reads(group, file, schema_of);

  DomainLease fresh;
  auto p = participant(fresh.id());
  Inbox<RobotState> state_inbox;
  Inbox<RobotObservationBatch> observation_inbox;
  Inbox<Heartbeat> heartbeat_inbox;
  auto state_reader = make_inbox_reader(*p, dds::kRobotState, state_inbox);
  auto observation_reader = make_inbox_reader(*p, dds::kRobotObservations, observation_inbox);
  auto heartbeat_reader = make_inbox_reader(*p, dds::kHeartbeat, heartbeat_inbox);
  group.start("replay", {bin_path("slamctl"), "--domain", std::to_string(fresh.id()), "--timeout", "30",
                         "replay", file, "--rate", "4"});
  ASSERT_EQ(group.wait_exit("replay", kExitTimeout), 0) << group.log("replay");
  EXPECT_NE(group.log("replay").find("replayed " + std::to_string(kStates + kObservations + kHeartbeats)),
            std::string::npos)
      << group.log("replay");
  EXPECT_EQ(state_inbox.items(), states);
  EXPECT_EQ(observation_inbox.items(), batches);
  EXPECT_EQ(heartbeat_inbox.items(), beats);
}

TEST(RecordReplayTest, InterruptedRecordingIsAValidFile) {
  TempDir dir("record");
  const std::string file = (dir / "interrupted.mcap").string();
  ProcessGroup group;
  DomainLease domain;
  auto p = participant(domain.id());
  auto writer = make_test_writer(*p, dds::kRobotState);
  group.start("record", {bin_path("slamctl"), "--domain", std::to_string(domain.id()), "record", file});
  publish_all(*writer, {robot_state(7)});
  // Acknowledged means in the recorder's reader history; its listener takes it a moment later.
  std::this_thread::sleep_for(1s);
  group.stop("record", SIGINT);
  ASSERT_EQ(group.wait_exit("record", kExitTimeout), 0) << group.log("record");
  auto mapped = mcap::MappedFile::open(file);
  ASSERT_TRUE(mapped) << mapped.message();
  auto contents = mcap::parse((*mapped)->bytes());
  ASSERT_TRUE(contents) << contents.message();
  EXPECT_EQ((recorded<RobotStatePubSubType, RobotState>(*contents, "slam/robot/state")),
            std::vector<RobotState>{robot_state(7)});
}

TEST(RecordReplayTest, ReplaySkipsChannelsOfUnknownTopicsWithALine) {
  TempDir dir("record");
  const std::string file = (dir / "foreign.mcap").string();
  {
    auto writer = mcap::Writer::create(file, "test");
    ASSERT_TRUE(writer);
    auto channel = (*writer)->add_channel(0, "/foreign/topic", "json");
    ASSERT_TRUE(channel);
    const std::string json = "{}";
    ASSERT_TRUE((*writer)->write_message(*channel, 1, 1, {reinterpret_cast<const uint8_t*>(json.data()), 2}));
    ASSERT_TRUE((*writer)->close());
  }
  ProcessGroup group;
  DomainLease domain;
  group.start("replay", {bin_path("slamctl"), "--domain", std::to_string(domain.id()), "--timeout", "1",
                         "replay", file});
  ASSERT_EQ(group.wait_exit("replay", kExitTimeout), 0) << group.log("replay");
  EXPECT_NE(group.log("replay").find("skipping channel '/foreign/topic'"), std::string::npos)
      << group.log("replay");
  EXPECT_NE(group.log("replay").find("replayed 0 messages"), std::string::npos) << group.log("replay");
}

}  // namespace
}  // namespace slam::testkit
