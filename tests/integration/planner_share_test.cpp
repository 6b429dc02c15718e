// Two slam-planners sharing the robots: this test plays the mapper (GridSnapshot), the gateway
// (RobotState) and the operator (NavGoal, PathRequest) on a DDS domain of its own. Every robot
// receives its waypoints, each robot's from one planner only (the writer of every WaypointCommand
// is counted per robot per period); each path request is executed by one planner; after `kill -9`
// of one planner its robots continue their goals under the other. The takeover time is measured and
// printed, not asserted (docs/deployment.md holds the figures).
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "common/fastdds/fast_topics.hpp"
#include "common/fastdds/requester.hpp"
#include "fastdds_inbox.hpp"
#include "process_group.hpp"

namespace slam {
namespace {

using namespace std::chrono_literals;
using testkit::bin_path;
using testkit::wait_until;
using Clock = std::chrono::steady_clock;

constexpr int kRobots = 12;
constexpr auto kPeriod = 1s;  // commands of one robot within a period must come from one planner

std::string robot_id(int i) {
  return "ps-" + std::to_string(i);
}
// Robot i stands in its own lane, 1 m from the next: far enough apart that fleet coordination
// never holds one robot for another.
double lane_y(int i) {
  return 1.0 + i;
}
// Each robot's own Direct goal: it stands still, so the target is resent as long as the goal runs.
Point2 target_of(int i) {
  Point2 p;
  p.x(8.0);
  p.y(lane_y(i));
  return p;
}

struct Command {
  std::string robot;
  std::string writer;  // the planner's writer GUID
  Point2 waypoint;
  Clock::time_point at;
};

class PlannerShareTest : public ::testing::Test {
 protected:
  void SetUp() override {
    for (const char* name : {"planner-a", "planner-b"}) {
      group.start(
          name, {bin_path("slam-planner"), "--domain", std::to_string(domain.id()), "--goals-resend-period-s",
                 "0.2", "--goal-store", group.dir() + "/goals-" + name + ".json"});
    }
    participant = std::move(*dds::Participant::create(domain.id(), "planner-share-test"));
    snapshots = testkit::make_test_writer(*participant, dds::kGridSnapshot);
    states = testkit::make_test_writer(*participant, dds::kRobotState);
    goals = testkit::make_test_writer(*participant, dds::kNavGoal);
    requests = testkit::make_test_writer(*participant, dds::kPathRequest);
    waypoint_reader = std::move(*dds::make_reader(
        *participant, dds::kWaypointCommand,
        [this](const WaypointCommand& c, const dds::fdds::SampleInfo& info) {
          std::ostringstream writer;
          writer << info.sample_identity.writer_guid();
          std::lock_guard lock(mutex);
          commands.push_back({c.robot_id().to_string(), writer.str(), c.waypoint(), Clock::now()});
        }));
    reply_reader = std::move(*dds::make_reader(*participant, dds::kPathReply,
                                               [this](const PathReply& r, const dds::fdds::SampleInfo& info) {
                                                 std::ostringstream writer;
                                                 writer << info.sample_identity.writer_guid();
                                                 std::lock_guard lock(mutex);
                                                 reply_writers[r.request_id()].insert(writer.str());
                                               }));
    heartbeat_reader =
        std::move(*dds::make_reader(*participant, dds::kHeartbeat, [this](const Heartbeat& h, const auto&) {
          if (h.service() != std::string("planner")) return;
          std::lock_guard lock(mutex);
          auto& values = planner_counters[h.instance_id().to_string()];
          for (const auto& c : h.counters()) values[c.name().to_string()] = c.value();
        }));
    ASSERT_TRUE(goals->wait_for_readers(60s, 2)) << group.log("planner-a") << group.log("planner-b");
    ASSERT_TRUE(states->wait_for_readers(60s, 2));
    ASSERT_TRUE(snapshots->wait_for_readers(60s, 2));
  }

  void TearDown() override {
    if (HasFailure()) std::cerr << group.log("planner-a") << group.log("planner-b");
  }

  void publish_world() {
    GridSnapshot s;
    s.layout_id(1);
    s.version(1);
    s.info().width(200);
    s.info().height(200);
    s.info().resolution(0.1);
    s.cells(std::vector<uint8_t>(200 * 200, 1));  // all free, 20 x 20 m
    ASSERT_TRUE(snapshots->write(s));
    for (int i = 0; i < kRobots; ++i) {
      RobotState st;
      st.robot_id(robot_id(i));
      st.presence(PRESENCE_ONLINE);
      st.battery(-1.0f);  // unknown, as a v1 robot's: 0 would be an empty battery (sent home)
      st.pose().x(1.0);
      st.pose().y(lane_y(i));
      ASSERT_TRUE(states->write(st));
      NavGoal g;
      g.robot_id(robot_id(i));
      g.goal_id(100 + static_cast<uint64_t>(i));
      g.mode(GOAL_DIRECT);
      g.target(target_of(i));
      ASSERT_TRUE(goals->write(g));
    }
  }

  // Counter `name` summed over the planners heard, and how many report at least `at_least`.
  int64_t counter_sum(const std::string& name) {
    std::lock_guard lock(mutex);
    int64_t sum = 0;
    for (const auto& [instance, values] : planner_counters) {
      const auto it = values.find(name);
      if (it != values.end()) sum += it->second;
    }
    return sum;
  }
  size_t planners_reporting(const std::string& name, int64_t at_least) {
    std::lock_guard lock(mutex);
    size_t n = 0;
    for (const auto& [instance, values] : planner_counters) {
      const auto it = values.find(name);
      n += it != values.end() && it->second >= at_least ? 1 : 0;
    }
    return n;
  }

  std::vector<Command> commands_since(Clock::time_point from) {
    std::lock_guard lock(mutex);
    std::vector<Command> out;
    for (const Command& c : commands)
      if (c.at >= from) out.push_back(c);
    return out;
  }

  // Every robot got commands in [from, to), and within each period each robot's came from one
  // writer; its waypoint is its own goal's target. Returns the writer of each robot.
  std::map<std::string, std::string> expect_one_planner_per_robot(Clock::time_point from,
                                                                  Clock::time_point to) {
    std::map<std::pair<std::string, int64_t>, std::set<std::string>> writers;  // (robot, period)
    std::map<std::string, std::string> last_writer;
    for (const Command& c : commands_since(from)) {
      if (c.at >= to) continue;
      const int64_t period = (c.at - from) / kPeriod;
      writers[{c.robot, period}].insert(c.writer);
      last_writer[c.robot] = c.writer;
      const int i = std::stoi(c.robot.substr(3));
      EXPECT_NEAR(c.waypoint.x(), target_of(i).x(), 1e-9) << c.robot;
      EXPECT_NEAR(c.waypoint.y(), target_of(i).y(), 1e-9) << c.robot;
    }
    EXPECT_EQ(last_writer.size(), static_cast<size_t>(kRobots)) << "robots without waypoints";
    for (const auto& [key, set] : writers)
      EXPECT_EQ(set.size(), 1u) << key.first << " got waypoints from " << set.size() << " planners in period "
                                << key.second;
    return last_writer;
  }

  testkit::DomainLease domain;
  testkit::ProcessGroup group;
  std::mutex mutex;
  std::vector<Command> commands;
  std::map<uint64_t, std::set<std::string>> reply_writers;
  std::map<std::string, std::map<std::string, int64_t>> planner_counters;
  std::unique_ptr<dds::Participant> participant;
  std::unique_ptr<dds::Writer<GridSnapshot>> snapshots;
  std::unique_ptr<dds::Writer<RobotState>> states;
  std::unique_ptr<dds::Writer<NavGoal>> goals;
  std::unique_ptr<dds::Writer<PathRequest>> requests;
  std::unique_ptr<dds::Reader<WaypointCommand>> waypoint_reader;
  std::unique_ptr<dds::Reader<PathReply>> reply_reader;
  std::unique_ptr<dds::Reader<Heartbeat>> heartbeat_reader;
};

TEST_F(PlannerShareTest, EachRobotDrivenByOnePlannerEachRequestAnsweredOnceAndTheSurvivorTakesOver) {
  ASSERT_NO_FATAL_FAILURE(publish_world());
  // Both planners warmed up, hearing each other, and sharing all the robots between them.
  ASSERT_TRUE(wait_until(
      [&] {
        return planners_reporting("planners_live", 2) == 2 && planners_reporting("robots_owned", 1) == 2 &&
               counter_sum("robots_owned") == kRobots;
      },
      30s))
      << "robots_owned " << counter_sum("robots_owned") << "\n"
      << group.log("planner-a") << group.log("planner-b");

  // Steady: every robot's waypoints from one planner per period, and both planners drive some.
  const auto steady_from = Clock::now();
  std::this_thread::sleep_for(3 * kPeriod);
  const auto owners = expect_one_planner_per_robot(steady_from, Clock::now());
  std::set<std::string> planner_writers;
  for (const auto& [robot, writer] : owners) planner_writers.insert(writer);
  EXPECT_EQ(planner_writers.size(), 2u);

  // Path requests: each executed by one planner (its owner), answered by it alone.
  auto requester = dds::Requester<PathReply>::create(*participant, dds::kPathReply, {200ms, 1000ms, 20s});
  ASSERT_TRUE(requester) << requester.message();
  constexpr int kRequests = 8;
  std::vector<uint64_t> ids;
  for (int i = 0; i < kRequests; ++i) {
    PathRequest r;
    r.client_id("planner-share-test");
    r.start().x(1.0);
    r.start().y(1.0);
    r.goal().x(2.0 + 0.5 * i);
    r.goal().y(5.0);
    r.algorithm("astar");
    r.time_budget_s(1.0);
    std::optional<PathReply> reply;
    reply = (*requester)->call(*requests, r);
    ASSERT_TRUE(reply) << "path request " << i << " unanswered";
    EXPECT_EQ(reply->status(), PLAN_OK) << reply->reason();
    ids.push_back(reply->request_id());
  }
  ASSERT_TRUE(wait_until([&] { return counter_sum("path_requests") == kRequests; }, 10s))
      << "path requests executed: " << counter_sum("path_requests") << " of " << kRequests;
  EXPECT_GT(counter_sum("path_requests_not_owned"), 0);
  {
    std::lock_guard lock(mutex);
    for (uint64_t id : ids) EXPECT_EQ(reply_writers[id].size(), 1u) << "request " << id;
  }

  // kill -9 one planner: its robots continue their goals under the other.
  group.stop("planner-a", SIGKILL);
  const auto killed_at = Clock::now();
  std::this_thread::sleep_for(500ms);  // nothing the killed planner sent is still arriving
  std::string survivor;
  ASSERT_TRUE(wait_until(
      [&] {
        const auto recent = commands_since(killed_at + 500ms);
        if (recent.empty()) return false;
        survivor = recent.front().writer;
        return true;
      },
      10s));
  std::set<std::string> orphans;
  for (const auto& [robot, writer] : owners)
    if (writer != survivor) orphans.insert(robot);
  EXPECT_FALSE(orphans.empty());
  std::map<std::string, double> taken_after_s;
  ASSERT_TRUE(wait_until(
      [&] {
        for (const Command& c : commands_since(killed_at)) {
          if (c.writer != survivor || orphans.count(c.robot) == 0 || taken_after_s.count(c.robot)) continue;
          taken_after_s[c.robot] = std::chrono::duration<double>(c.at - killed_at).count();
        }
        return taken_after_s.size() == orphans.size();
      },
      20s))
      << "robots taken over: " << taken_after_s.size() << " of " << orphans.size() << "\n"
      << group.log("planner-b");
  double takeover_s = 0.0;
  for (const auto& [robot, s] : taken_after_s) takeover_s = std::max(takeover_s, s);

  // After the takeover: every robot from the survivor, its own goal's target.
  const auto after_from = Clock::now();
  std::this_thread::sleep_for(2 * kPeriod);
  for (const auto& [robot, writer] : expect_one_planner_per_robot(after_from, Clock::now()))
    EXPECT_EQ(writer, survivor) << robot;
  EXPECT_TRUE(wait_until([&] { return planners_reporting("robots_owned", kRobots) == 1; }, 10s));

  std::printf("[ figures ] planner takeover after kill -9: %.2f s (%zu of %d robots moved)\n", takeover_s,
              orphans.size(), kRobots);
  RecordProperty("takeover_s", std::to_string(takeover_s));
}

}  // namespace
}  // namespace slam
