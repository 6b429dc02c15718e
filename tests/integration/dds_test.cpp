// The Fast DDS edge of the common library, between two participants: writes report success,
// a fleet's worth of keyed instances all arrive (Fast DDS's default limit is 10), transient-local
// state reaches a late joiner, command streams deliver far more than 10 requests, and a lagging
// observation reader costs the writer a bounded history: it loses old samples, counted.
#include <fastrtps/xmlparser/XMLProfileManager.h>
#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <set>

#include "common/fastdds/fast_topics.hpp"
#include "process_group.hpp"

namespace slam::testkit {
namespace {

std::unique_ptr<dds::Participant> participant(int domain, const char* name) {
  auto p = dds::Participant::create(domain, name);
  if (!p) throw std::runtime_error(p.message());
  return std::move(*p);
}

struct Pair {
  DomainLease domain;
  std::unique_ptr<dds::Participant> a = participant(domain.id(), "dds_test_a");
  std::unique_ptr<dds::Participant> b = participant(domain.id(), "dds_test_b");
};

TEST(DdsTest, FiveHundredRobotStatesAllArrive) {
  Pair p;
  std::mutex mutex;
  std::set<std::string> seen;
  auto reader = dds::make_reader(*p.b, dds::kRobotState, [&](const RobotState& s, const auto&) {
    std::lock_guard lock(mutex);
    seen.insert(s.robot_id().to_string());
  });
  ASSERT_TRUE(reader) << reader.message();
  auto writer = dds::make_writer(*p.a, dds::kRobotState);
  ASSERT_TRUE(writer) << writer.message();
  ASSERT_TRUE(wait_until([&] { return (*writer)->matched_readers() == 1; }, 10s));
  RobotState s;
  for (int i = 0; i < 500; ++i) {
    s.robot_id("robot-" + std::to_string(i));
    ASSERT_TRUE((*writer)->write(s)) << "write " << i;
  }
  EXPECT_TRUE(wait_until(
      [&] {
        std::lock_guard lock(mutex);
        return seen.size() == 500;
      },
      10s))
      << seen.size();
}

TEST(DdsTest, LateJoinerGetsTheLatestStatePerKey) {
  Pair p;
  auto writer = dds::make_writer(*p.a, dds::kRobotState);
  ASSERT_TRUE(writer);
  RobotState s;
  for (int i = 0; i < 50; ++i) {
    s.robot_id("robot-" + std::to_string(i % 25));
    s.messages(static_cast<uint64_t>(i));
    ASSERT_TRUE((*writer)->write(s));
  }
  std::vector<RobotState> got;
  auto reader = dds::make_reader(*p.b, dds::kRobotState);
  ASSERT_TRUE(reader);
  ASSERT_TRUE(wait_until(
      [&] {
        (*reader)->take(got);
        return got.size() >= 25;
      },
      10s))
      << got.size();
  EXPECT_EQ(got.size(), 25u);
  for (const auto& r : got) EXPECT_GE(r.messages(), 25u) << "an older sample of " << r.robot_id().to_string();
}

TEST(DdsTest, CommandStreamsCarryManyRequests) {
  Pair p;
  std::atomic<int> replies{0};
  auto reader = dds::make_reader(*p.b, dds::kPathReply, [&](const PathReply&, const auto&) { ++replies; });
  ASSERT_TRUE(reader);
  auto writer = dds::make_writer(*p.a, dds::kPathReply);
  ASSERT_TRUE(writer);
  ASSERT_TRUE(wait_until([&] { return (*writer)->matched_readers() == 1; }, 10s));
  PathReply r;
  for (uint64_t i = 0; i < 200; ++i) {
    r.request_id(i);
    ASSERT_TRUE((*writer)->write(r)) << "write " << i;
    if (i % 50 == 49) {
      ASSERT_TRUE((*writer)->wait_for_acknowledgments(std::chrono::milliseconds(5000)));
    }
  }
  EXPECT_TRUE(wait_until([&] { return replies == 200; }, 10s)) << replies;
}

// Overload: a reader that stops taking samples (its listener blocked, as a starved process would)
// while the writer goes on. The writer keeps only the last few observations per robot for repair
// (topics::kObservationQos), so once the reader's socket buffer overflows it cannot get the rest
// back: it loses them and counts them (SAMPLE_LOST). Every sample ends up received or counted lost,
// and no write was refused or blocked for the slow reader.
// Fast DDS hands samples between participants of one process straight to the reader on the
// writer's thread; services are separate processes and talk over UDP. UDP for the life of this.
class InterprocessDelivery {
 public:
  InterprocessDelivery() : saved_(eprosima::fastrtps::xmlparser::XMLProfileManager::library_settings()) {
    eprosima::fastrtps::LibrarySettingsAttributes udp = saved_;
    udp.intraprocess_delivery = eprosima::fastrtps::INTRAPROCESS_OFF;
    eprosima::fastrtps::xmlparser::XMLProfileManager::library_settings(udp);
  }
  ~InterprocessDelivery() { eprosima::fastrtps::xmlparser::XMLProfileManager::library_settings(saved_); }
  InterprocessDelivery(const InterprocessDelivery&) = delete;
  InterprocessDelivery& operator=(const InterprocessDelivery&) = delete;

 private:
  eprosima::fastrtps::LibrarySettingsAttributes saved_;
};

TEST(DdsTest, ALaggingObservationReaderLosesOldSamplesAndCountsThem) {
  InterprocessDelivery udp;
  Pair p;
  std::mutex gate;
  std::unique_lock blocked(gate);
  std::atomic<int64_t> received{0};
  auto reader =
      dds::make_reader(*p.b, dds::kRobotObservations, [&](const RobotObservationBatch&, const auto&) {
        std::lock_guard wait(gate);
        ++received;
      });
  ASSERT_TRUE(reader) << reader.message();
  auto writer = dds::make_writer(*p.a, dds::kRobotObservations);
  ASSERT_TRUE(writer) << writer.message();
  ASSERT_TRUE((*writer)->wait_for_readers(10s));
  // 16 kB samples, 16 MB in all: several times what the reader's socket buffer holds (4 MB, which
  // Linux doubles), and far more than the writer keeps (64 batches).
  constexpr int kSent = 1000;
  RobotObservationBatch batch;
  batch.gateway_id("host:1");
  batch.observations().resize(1);
  batch.observations()[0].robot_id("robot-0");
  batch.observations()[0].hits(std::vector<Point2>(1000));
  for (int i = 0; i < kSent; ++i) {
    batch.batch_seq(static_cast<uint64_t>(i + 1));
    batch.observations()[0].seq(static_cast<uint64_t>(i + 1));
    ASSERT_TRUE((*writer)->write(batch)) << "write " << i;
  }
  blocked.unlock();
  const auto accounted = [&] { return received + (*reader)->samples_lost(); };
  EXPECT_TRUE(wait_until([&] { return accounted() == kSent; }, 30s))
      << received << " received + " << (*reader)->samples_lost() << " lost of " << kSent;
  EXPECT_GT((*reader)->samples_lost(), 0) << "the writer kept every sample for the lagging reader";
  EXPECT_GT(received, 0);
}

}  // namespace
}  // namespace slam::testkit
