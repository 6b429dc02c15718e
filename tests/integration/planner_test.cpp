// slam-planner as a black box: this test plays the mapper (GridSnapshot, GridTiles), the gateway
// (RobotState) and the operator (NavGoal, PathRequest) on a DDS domain of its own, and checks the
// planner's PathReply, WaypointCommand and RobotPath samples. Generous timeouts: CI machines are loaded.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "common/core/grid_tiles.hpp"
#include "common/fastdds/fast_topics.hpp"
#include "fastdds_inbox.hpp"
#include "process_group.hpp"

namespace slam {
namespace {

using namespace std::chrono_literals;
using testkit::Inbox;
using testkit::wait_until;

constexpr double kRes = 0.1;
constexpr uint8_t kFree = 1;
constexpr uint8_t kOccupied = 2;
constexpr uint8_t kUnknown = 0;

Point2 pt(double x, double y) {
  Point2 p;
  p.x(x);
  p.y(y);
  return p;
}

// The test's own copy of the map it publishes, to judge the planner's paths against.
struct TestMap {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<uint8_t> cells;

  TestMap(uint32_t w, uint32_t h, uint8_t fill) : width(w), height(h), cells(size_t{w} * h, fill) {}
  void fill(uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1, uint8_t v) {  // inclusive box
    for (uint32_t y = y0; y <= y1; ++y)
      for (uint32_t x = x0; x <= x1; ++x) cells[size_t{y} * width + x] = v;
  }
  bool occupied(double x, double y) const {
    const auto cx = static_cast<int64_t>(std::floor(x / kRes));
    const auto cy = static_cast<int64_t>(std::floor(y / kRes));
    if (cx < 0 || cy < 0 || cx >= width || cy >= height) return true;
    return cells[static_cast<size_t>(cy) * width + static_cast<size_t>(cx)] == kOccupied;
  }
  // True when every point along the path, sampled every 5 mm, lies in a non-occupied cell.
  bool clear(const std::vector<Point2>& path) const {
    for (size_t i = 1; i < path.size(); ++i) {
      const double dx = path[i].x() - path[i - 1].x();
      const double dy = path[i].y() - path[i - 1].y();
      const int steps = std::max(1, static_cast<int>(std::hypot(dx, dy) / 0.005));
      for (int s = 0; s <= steps; ++s) {
        const double t = static_cast<double>(s) / steps;
        if (occupied(path[i - 1].x() + t * dx, path[i - 1].y() + t * dy)) return false;
      }
    }
    return true;
  }
  GridSnapshot snapshot(uint64_t version) const {
    GridSnapshot s;
    s.layout_id(1);
    s.version(version);
    s.info().width(width);
    s.info().height(height);
    s.info().resolution(kRes);
    s.info().origin(pt(0, 0));
    s.cells(cells);
    return s;
  }
};

// 10 m x 6 m, all free, a wall at x = 4.9..5.1 m with two gaps: A at y 2.0..2.6, B at y 4.5..5.3.
TestMap walled_map() {
  TestMap map(100, 60, kFree);
  map.fill(49, 0, 50, 59, kOccupied);
  map.fill(49, 20, 50, 25, kFree);
  map.fill(49, 45, 50, 52, kFree);
  return map;
}

class PlannerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    group_.start("planner", {testkit::bin_path("slam-planner"), "--domain", std::to_string(domain_.id()),
                             "--goals-resend-period-s", "0.5", "--request-workers", "2", "--no-share",
                             "--goal-store", group_.dir() + "/goals.json"});
    auto p = dds::Participant::create(domain_.id(), "planner_test");
    ASSERT_TRUE(p) << p.message();
    participant_ = std::move(*p);
    snapshots_ = testkit::make_test_writer(*participant_, dds::kGridSnapshot);
    patches_ = testkit::make_test_writer(*participant_, dds::kGridTiles);
    states_ = testkit::make_test_writer(*participant_, dds::kRobotState);
    goals_ = testkit::make_test_writer(*participant_, dds::kNavGoal);
    requests_ = testkit::make_test_writer(*participant_, dds::kPathRequest);
    reply_reader_ = testkit::make_inbox_reader(*participant_, dds::kPathReply, replies_);
    waypoint_reader_ = testkit::make_inbox_reader(*participant_, dds::kWaypointCommand, waypoints_);
    path_reader_ = testkit::make_inbox_reader(*participant_, dds::kRobotPath, paths_);
    heartbeat_reader_ = testkit::make_inbox_reader(*participant_, dds::kHeartbeat, heartbeats_);
    ASSERT_TRUE(wait_until(
        [&] {
          return snapshots_->matched_readers() > 0 && patches_->matched_readers() > 0 &&
                 states_->matched_readers() > 0 && goals_->matched_readers() > 0 &&
                 requests_->matched_readers() > 0 && reply_reader_->matched_writers() > 0 &&
                 waypoint_reader_->matched_writers() > 0 && path_reader_->matched_writers() > 0;
        },
        60s))
        << "slam-planner never matched the test's topics\n"
        << group_.log("planner");
    // Matching is seen from this side first; let the planner's writers match our readers too.
    std::this_thread::sleep_for(dds::kMatchSettle);
  }

  void TearDown() override {
    if (HasFailure()) std::cerr << "--- slam-planner log ---\n" << group_.log("planner");
  }

  // The planner's latest heartbeat value of `name` (-1 before the first heartbeat).
  int64_t counter(const std::string& name) const {
    const auto hb = heartbeats_.last([](const Heartbeat& h) { return h.service() == "planner"; });
    if (!hb) return -1;
    for (const Counter& c : hb->counters())
      if (c.name() == name) return c.value();
    return -1;
  }

  void publish_map(const TestMap& map, uint64_t version) {
    snapshots_->write(map.snapshot(version));
    ASSERT_TRUE(wait_until([&] { return counter("snapshots") >= 1; }, 30s))
        << "the planner never took the map";
  }

  void move_robot(const std::string& id, double x, double y) {
    RobotState s;
    s.robot_id(id);
    s.presence(PRESENCE_ONLINE);
    s.battery(-1.0f);  // unknown, as a v1 robot's: 0 would be an empty battery (sent home)
    s.pose().x(x);
    s.pose().y(y);
    states_->write(s);
  }

  void send_goal(const std::string& id, uint64_t goal_id, GoalMode mode, Point2 target) {
    NavGoal g;
    g.robot_id(id);
    g.goal_id(goal_id);
    g.mode(mode);
    g.target(target);
    goals_->write(g);
  }

  PathReply request(uint64_t id, Point2 start, Point2 goal, const std::string& algorithm, double budget) {
    send_request(id, start, goal, algorithm, budget);
    return wait_reply(id);
  }

  void send_request(uint64_t id, Point2 start, Point2 goal, const std::string& algorithm, double budget) {
    PathRequest r;
    r.request_id(id);
    r.client_id("planner_test");
    r.start(start);
    r.goal(goal);
    r.algorithm(algorithm);
    r.time_budget_s(budget);
    requests_->write(r);
  }

  PathReply wait_reply(uint64_t id) {
    const auto match = [id](const PathReply& r) { return r.request_id() == id; };
    EXPECT_TRUE(wait_until([&] { return replies_.last(match).has_value(); }, 60s))
        << "no reply to request " << id;
    return replies_.last(match).value_or(PathReply{});
  }

  std::optional<RobotPath> last_path(const std::string& id, uint64_t goal_id) const {
    return paths_.last([&](const RobotPath& p) { return p.robot_id() == id && p.goal_id() == goal_id; });
  }

  std::optional<WaypointCommand> last_command(const std::string& id) const {
    return waypoints_.last([&](const WaypointCommand& w) { return w.robot_id() == id; });
  }

  testkit::DomainLease domain_;
  testkit::ProcessGroup group_;
  std::unique_ptr<dds::Participant> participant_;
  std::unique_ptr<dds::Writer<GridSnapshot>> snapshots_;
  std::unique_ptr<dds::Writer<GridTiles>> patches_;
  std::unique_ptr<dds::Writer<RobotState>> states_;
  std::unique_ptr<dds::Writer<NavGoal>> goals_;
  std::unique_ptr<dds::Writer<PathRequest>> requests_;
  Inbox<PathReply> replies_;
  Inbox<WaypointCommand> waypoints_;
  Inbox<RobotPath> paths_;
  Inbox<Heartbeat> heartbeats_;
  std::unique_ptr<dds::Reader<PathReply>> reply_reader_;
  std::unique_ptr<dds::Reader<WaypointCommand>> waypoint_reader_;
  std::unique_ptr<dds::Reader<RobotPath>> path_reader_;
  std::unique_ptr<dds::Reader<Heartbeat>> heartbeat_reader_;
  uint64_t corrections_sent_ = 0;
};

bool near(const Point2& a, const Point2& b, double tol = 1e-6) {
  return std::hypot(a.x() - b.x(), a.y() - b.y()) <= tol;
}

TEST_F(PlannerTest, AnswersPathRequestsAroundTheWallAndRejectsBadOnesWithAReason) {
  const TestMap map = walled_map();
  publish_map(map, 5);

  for (const auto& [id, algorithm] : {std::pair<uint64_t, std::string>{1, "astar"}, {2, "rrtconnect"}}) {
    const PathReply r = request(id, pt(2, 1), pt(8, 1), algorithm, 2.0);
    ASSERT_EQ(r.status(), PLAN_OK) << algorithm << ": " << r.reason();
    EXPECT_EQ(r.client_id(), "planner_test");
    ASSERT_GE(r.path().size(), 3u) << algorithm << ": a path through the wall's gap bends";
    EXPECT_TRUE(near(r.path().front(), pt(2, 1)));
    EXPECT_TRUE(near(r.path().back(), pt(8, 1)));
    EXPECT_TRUE(map.clear(r.path())) << algorithm << " path crosses an occupied cell";
    EXPECT_GT(r.length_m(), 6.0);
    EXPECT_GE(r.planning_time_s(), 0.0);
  }

  // Concurrent requests: every one is answered, each with its own id.
  for (uint64_t id = 10; id < 16; ++id) {
    send_request(id, pt(1, 0.5 + 0.5 * static_cast<double>(id - 10)), pt(9, 5), id % 2 ? "prmstar" : "astar",
                 0.5);
  }
  for (uint64_t id = 10; id < 16; ++id) {
    const PathReply r = wait_reply(id);
    EXPECT_EQ(r.status(), PLAN_OK) << "request " << id << ": " << r.reason();
    EXPECT_TRUE(map.clear(r.path())) << "request " << id;
  }

  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Bad {
    uint64_t id;
    Point2 start, goal;
    std::string algorithm;
    double budget;
    PlanStatus status;
    std::string reason;
  };
  const std::vector<Bad> bad = {
      {20, pt(nan, 1), pt(8, 1), "astar", 1.0, PLAN_INVALID_REQUEST, "start is not finite"},
      {21, pt(2, 1), pt(8, 1), "dijkstra", 1.0, PLAN_INVALID_REQUEST, "unknown algorithm 'dijkstra'"},
      {22, pt(2, 1), pt(8, 1), "rrtconnect", 0.0, PLAN_INVALID_REQUEST, "time budget"},
      {23, pt(2, 1), pt(50, 1), "astar", 1.0, PLAN_INVALID_REQUEST, "outside the map"},
      {24, pt(2, 1), pt(5.0, 1.0), "astar", 1.0, PLAN_GOAL_BLOCKED, "obstacle"},
  };
  for (const Bad& b : bad) send_request(b.id, b.start, b.goal, b.algorithm, b.budget);
  for (const Bad& b : bad) {
    const PathReply r = wait_reply(b.id);
    EXPECT_EQ(r.status(), b.status) << "request " << b.id << ": " << r.reason();
    EXPECT_NE(r.reason().to_string().find(b.reason), std::string::npos)
        << "request " << b.id << " reason: " << r.reason();
    EXPECT_TRUE(r.path().empty());
  }
  EXPECT_TRUE(wait_until([&] { return counter("replies_invalid_request") >= 4; }, 10s));
  EXPECT_TRUE(group_.running("planner"));
}

TEST_F(PlannerTest, StreamsWaypointsInOrderAndReplansWhenAPatchBlocksThePath) {
  TestMap map = walled_map();
  publish_map(map, 5);
  move_robot("r1", 2, 1);
  ASSERT_TRUE(wait_until([&] { return counter("robot_positions") >= 1; }, 30s));

  // A goal for a robot not seen yet waits for it (status NONE, the reason says so); bad goals get a
  // clear FAILED status with the reason, and nothing is sent.
  send_goal("ghost", 1, GOAL_PLANNED, pt(8, 1));
  ASSERT_TRUE(wait_until([&] { return last_path("ghost", 1).has_value(); }, 30s));
  EXPECT_EQ(last_path("ghost", 1)->status(), GOAL_STATUS_NONE);
  EXPECT_NE(last_path("ghost", 1)->reason().to_string().find("unknown robot"), std::string::npos);
  send_goal("r1", 1, GOAL_PLANNED, pt(std::numeric_limits<double>::infinity(), 1));
  ASSERT_TRUE(wait_until([&] { return last_path("r1", 1).has_value(); }, 30s));
  EXPECT_EQ(last_path("r1", 1)->status(), GOAL_STATUS_FAILED);
  EXPECT_NE(last_path("r1", 1)->reason().to_string().find("not finite"), std::string::npos);
  EXPECT_FALSE(last_command("r1").has_value());

  send_goal("r1", 2, GOAL_PLANNED, pt(8, 1));
  ASSERT_TRUE(wait_until([&] { return last_command("r1").has_value(); }, 30s)) << "no waypoint for r1";
  const auto first = last_path("r1", 2);
  ASSERT_TRUE(first && first->status() == GOAL_STATUS_ACTIVE && !first->waypoints().empty());
  EXPECT_TRUE(near(last_command("r1")->waypoint(), first->waypoints().front()));
  for (const Point2& w : first->waypoints()) EXPECT_LT(w.y(), 4.0) << "the first plan should use gap A";
  // Unchanged waypoints are re-sent (every 0.5 s here) with a new sequence number.
  const uint64_t seq = last_command("r1")->seq();
  ASSERT_TRUE(wait_until([&] { return last_command("r1")->seq() > seq; }, 10s));
  EXPECT_TRUE(near(last_command("r1")->waypoint(), first->waypoints().front()));

  // The mapper closes gap A: the planner must re-plan through gap B.
  map.fill(49, 20, 50, 25, kOccupied);
  DirtyTiles dirty;
  dirty.reset({static_cast<int32_t>(map.width), static_cast<int32_t>(map.height), kGridTileSide});
  for (int32_t y = 20; y <= 25; ++y) {
    dirty.mark(49, y);
    dirty.mark(50, y);
  }
  EncodedTiles encoded;
  encode_tiles(map.cells, dirty, encoded);
  GridTiles patch;
  patch.layout_id(1);
  patch.version(6);
  patch.tile_side(static_cast<uint16_t>(kGridTileSide));
  patch.encoding(static_cast<uint8_t>(encoded.encoding));
  patch.tiles(encoded.tiles);
  patch.data(encoded.data);
  patches_->write(patch);
  const auto via_gap_b = [&] {
    const auto p = last_path("r1", 2);
    if (!p || p->status() != GOAL_STATUS_ACTIVE) return false;
    for (const Point2& w : p->waypoints())
      if (w.y() > 4.4) return true;
    return false;
  };
  ASSERT_TRUE(wait_until(via_gap_b, 30s)) << "no re-plan after the patch";
  const std::vector<Point2> route = last_path("r1", 2)->waypoints();
  EXPECT_TRUE(map.clear(route));
  EXPECT_TRUE(wait_until([&] { return counter("replans") >= 1; }, 10s));

  // Drive: each waypoint must be the one commanded next; the robot reports from it.
  for (size_t i = 0; i < route.size(); ++i) {
    ASSERT_TRUE(wait_until([&] { return near(last_command("r1")->waypoint(), route[i]); }, 30s))
        << "waypoint " << i << " (" << route[i].x() << ", " << route[i].y() << ") never commanded; last "
        << last_command("r1")->waypoint().x() << ", " << last_command("r1")->waypoint().y();
    move_robot("r1", route[i].x(), route[i].y());
  }
  ASSERT_TRUE(wait_until([&] { return last_path("r1", 2)->status() == GOAL_STATUS_REACHED; }, 30s));
  EXPECT_TRUE(wait_until([&] { return counter("goals_reached") >= 1; }, 10s));
}

TEST_F(PlannerTest, ExploringRobotsGetDifferentFrontiers) {
  // 12 m x 6 m: known free in the middle (x 3..9 m), unknown left and right, walls top and bottom.
  TestMap map(120, 60, kUnknown);
  map.fill(30, 1, 89, 58, kFree);
  map.fill(0, 0, 119, 0, kOccupied);
  map.fill(0, 59, 119, 59, kOccupied);
  publish_map(map, 1);
  move_robot("r1", 4, 3);
  move_robot("r2", 8, 3);
  ASSERT_TRUE(wait_until([&] { return counter("robot_positions") >= 2; }, 30s));

  send_goal("*", 7, GOAL_EXPLORE, pt(0, 0));
  const auto exploring = [&](const std::string& id) {
    const auto p = last_path(id, 7);
    return p && p->mode() == GOAL_EXPLORE && p->status() == GOAL_STATUS_ACTIVE && !p->waypoints().empty();
  };
  ASSERT_TRUE(wait_until([&] { return exploring("r1") && exploring("r2"); }, 30s));
  const Point2 t1 = last_path("r1", 7)->target();
  const Point2 t2 = last_path("r2", 7)->target();
  EXPECT_GT(std::hypot(t1.x() - t2.x(), t1.y() - t2.y()), 3.0) << "both robots chase the same frontier";
  EXPECT_LT(t1.x(), 3.5) << "r1 should take the left frontier";
  EXPECT_GT(t2.x(), 8.5) << "r2 should take the right frontier";
  EXPECT_TRUE(wait_until([&] { return last_command("r1") && last_command("r2"); }, 30s));
}

TEST_F(PlannerTest, AnExploringRobotThatGrowsUncertainGoesBackToWhereItWasTied) {
  // The mapper's part: each robot's correction, with how well the robot is known in the map.
  auto corrections = testkit::make_test_writer(*participant_, dds::kPoseCorrection);
  ASSERT_TRUE(wait_until([&] { return corrections->matched_readers() > 0; }, 30s));
  const auto correct = [&](double sigma_m) {
    PoseCorrection c;
    c.robot_id("r1");
    c.version(corrections_sent_ + 1);
    c.covariance({sigma_m * sigma_m, 0.0, 0.0, sigma_m * sigma_m, 0.0, 1e-4});
    corrections->write(c);
    ++corrections_sent_;
  };
  TestMap map(120, 60, kUnknown);
  map.fill(30, 1, 89, 58, kFree);
  map.fill(0, 0, 119, 0, kOccupied);
  map.fill(0, 59, 119, 59, kOccupied);
  publish_map(map, 1);
  const auto at = [&](double x, double y, int64_t positions) {
    RobotState st;
    st.robot_id("r1");
    st.presence(PRESENCE_ONLINE);
    st.battery(-1.0f);
    st.pose().x(x);
    st.pose().y(y);
    st.last_seen_ns(positions * 1'000'000'000);  // newer each time: the planner keeps the newest
    states_->write(st);
    ASSERT_TRUE(wait_until([&] { return counter("robot_positions") >= positions; }, 30s));
  };
  at(4, 3, 1);
  correct(0.08);
  std::this_thread::sleep_for(500ms);
  correct(0.04);  // shrank: tied to the old map here
  std::this_thread::sleep_for(500ms);
  send_goal("r1", 8, GOAL_EXPLORE, pt(0, 0));
  const auto path = [&] { return last_path("r1", 8); };
  ASSERT_TRUE(wait_until([&] { return path() && !path()->waypoints().empty(); }, 30s));
  correct(0.09);  // off into new ground: less sure, still exploring
  std::this_thread::sleep_for(500ms);
  at(5.5, 3, 2);
  EXPECT_EQ(counter("revisits"), 0);
  correct(0.15);
  ASSERT_TRUE(wait_until([&] { return counter("revisits") >= 1; }, 30s));
  ASSERT_TRUE(wait_until([&] { return path() && near(path()->target(), pt(4, 3), 0.15); }, 30s))
      << "target (" << path()->target().x() << ", " << path()->target().y() << ")";
  EXPECT_EQ(path()->mode(), GOAL_EXPLORE);
  EXPECT_EQ(path()->status(), GOAL_STATUS_ACTIVE);
  // Tied again on the way back: it explores on, to a frontier.
  at(5, 3, 3);
  correct(0.05);
  EXPECT_TRUE(
      wait_until([&] { return path() && (path()->target().x() < 3.5 || path()->target().x() > 8.5); }, 30s))
      << "target (" << path()->target().x() << ", " << path()->target().y() << ")";
  EXPECT_EQ(counter("revisits"), 1);
}

TEST(PlannerCommandLine, HelpExitsZeroAndBadConfigExitsTwoWithOneLine) {
  testkit::ProcessGroup group;
  group.start("help", {testkit::bin_path("slam-planner"), "--help"});
  EXPECT_EQ(group.wait_exit("help", 30s), 0);
  EXPECT_NE(group.log("help").find("--goals-resend-period-s"), std::string::npos);
  group.start("bad", {testkit::bin_path("slam-planner"), "--goals-reach-tolerance-m", "-1"});
  EXPECT_EQ(group.wait_exit("bad", 30s), 2);
  const std::string log = group.log("bad");
  EXPECT_NE(log.find("reach_tolerance_m must be positive"), std::string::npos) << log;
  EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 1) << log;
}

}  // namespace
}  // namespace slam
