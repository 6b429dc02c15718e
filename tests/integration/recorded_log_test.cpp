// A simulated benchmark log end to end, so the project needs no recorded one. A drive through the
// office is written with the simulator's log recorder (the library behind --record-log) as a
// CARMEN log and a relation file of its ground truth; slam-simulator --play sends the log through a
// real mosquitto, slam-gateway and slam-mapper (pose correction on), `slamctl trajectory` exports the
// robot's trajectory as TUM text with the log's stamps, and the benchmark's relation metric scores
// it: every relation's stamps found, a loose bound on the mean error. A second test runs
// slam-simulator --record-log itself and reads what it wrote.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/fastdds/fast_topics.hpp"
#include "eval/relation_metric.hpp"
#include "fastdds_inbox.hpp"
#include "mqtt_test_client.hpp"
#include "process_group.hpp"
#include "simulator/core/builtin_worlds.hpp"
#include "simulator/core/log_recorder.hpp"
#include "simulator/core/simulation.hpp"
#include "simulator/robot_log/carmen_log.hpp"
#include "temp_dir.hpp"

namespace slam::testkit {
namespace {

constexpr const char* kPlayedRobot = "recorded-1";
constexpr double kDriveS = 60.0;          // simulated seconds of driving: 600 scans
constexpr double kPlayRate = 10.0;        // x real time: the drive plays in 6 s
constexpr double kMaxMeanErrorM = 0.15;   // the loose bound on the mean translational error
constexpr double kMaxMeanErrorDeg = 3.0;  // and on the mean rotational one

// Poses by stamp from `slamctl trajectory --format tum` ("stamp x y z qx qy qz qw", yaw only).
struct Trajectory {
  std::vector<double> stamps;
  std::vector<Pose> poses;
};

Trajectory read_tum(const std::string& path) {
  Trajectory out;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    std::istringstream fields(line);
    double stamp = 0, x = 0, y = 0, z = 0, qx = 0, qy = 0, qz = 0, qw = 0;
    if (!(fields >> stamp >> x >> y >> z >> qx >> qy >> qz >> qw))
      throw std::runtime_error("bad TUM line: " + line);
    out.stamps.push_back(stamp);
    out.poses.push_back({x, y, 2 * std::atan2(qz, qw)});
  }
  return out;
}

// One robot random-walking the office for kDriveS simulated seconds with the simulator's default
// sensor and drift, its odometry starting at (0, 0, 0) as a real robot's; every report recorded.
// Returns the scans written.
int64_t record_drive(const std::string& prefix, const std::string& robot) {
  auto world = sim::builtin_world("office");
  if (!world) throw std::runtime_error(world.message());
  sim::SimulationConfig config;
  config.random_walk = true;
  config.seed = 5;
  config.odom_frame = sim::OdomFrame::Start;
  auto simulation = sim::Simulation::create(std::move(*world), config);
  if (!simulation) throw std::runtime_error(simulation.message());
  auto spawned = simulation->spawn_random(1);
  if (!spawned) throw std::runtime_error(spawned.message());
  auto recorder = sim::LogRecorder::create(prefix, "office");
  if (!recorder) throw std::runtime_error(recorder.message());
  while (simulation->time() < kDriveS)
    for (sim::RobotReport report : simulation->step()) {
      report.robot_id = robot;
      if (auto s = recorder->add(report); !s) throw std::runtime_error(s.message());
    }
  if (auto s = recorder->finish(); !s) throw std::runtime_error(s.message());
  return recorder->scans();
}

class RecordedLogTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string d = std::to_string(domain.id());
    group.start("gateway", {bin_path("slam-gateway"), "--domain", d, "--broker",
                            "tcp://127.0.0.1:" + std::to_string(port), "--no-share"});
    group.start("mapper", {bin_path("slam-mapper"), "--domain", d, "--store", group.dir() + "/map.db"});
    auto p = dds::Participant::create(domain.id(), "recorded-log-test");
    if (!p) throw std::runtime_error(p.message());
    participant = std::move(*p);
    heartbeat_reader = make_inbox_reader(*participant, dds::kHeartbeat, heartbeats);
    ASSERT_EQ(warm_up.connect(), 0);
    // The mapper starts 2.5 s late (one mapper per domain) and the gateway says it is connected
    // before the broker has its subscription: a warm-up robot reports until the mapper has
    // integrated one of its messages, so the player's first scan is not lost.
    ASSERT_TRUE(wait_until(
        [&] {
          warm_up.publish("v2/robot/warm-up/pose", std::string_view(R"({"x": 0, "y": 0})"), 0);
          return mapper_observations() > 0;
        },
        30s, 100ms))
        << group.log("gateway") << group.log("mapper");
  }
  void TearDown() override {
    if (!HasFailure()) return;
    for (const char* s : {"gateway", "mapper", "player"}) std::cerr << s << " log:\n" << group.log(s) << "\n";
  }

  // The mapper's `observations` counter in its latest heartbeat.
  int64_t mapper_observations() const {
    const auto beat = heartbeats.last([](const Heartbeat& h) { return h.service().to_string() == "mapper"; });
    if (!beat) return 0;
    for (const Counter& c : beat->counters())
      if (c.name().to_string() == "observations") return c.value();
    return 0;
  }

  // slamctl with `args`: exit code, and its output.
  std::pair<int, std::string> ctl(std::vector<std::string> args) {
    const std::string name = "slamctl" + std::to_string(++runs);
    std::vector<std::string> argv{bin_path("slamctl"), "--domain", std::to_string(domain.id()), "--timeout",
                                  "10"};
    argv.insert(argv.end(), args.begin(), args.end());
    group.start(name, argv);
    const int code = group.wait_exit(name, 60s);
    return {code, group.log(name)};
  }

  DomainLease domain;
  ProcessGroup group;
  int port = group.start_mosquitto();
  MqttTestClient warm_up{port, "recorded-log-test"};
  Inbox<Heartbeat> heartbeats;
  std::unique_ptr<dds::Participant> participant;
  std::unique_ptr<dds::Reader<Heartbeat>> heartbeat_reader;
  int runs = 0;
};

TEST_F(RecordedLogTest, APlayedSimulatedLogKeepsToItsRelations) {
  const TempDir dir("recorded-log");
  const std::string prefix = (dir / "office").string();
  const int64_t scans = record_drive(prefix, "sim-1");
  const std::string log = prefix + "-sim-1.clf", relations_file = prefix + "-sim-1.relations";

  group.start("player",
              {bin_path("slam-simulator"), "--broker", "tcp://127.0.0.1:" + std::to_string(port), "--play",
               log, "--play-robot-id", kPlayedRobot, "--play-rate", std::to_string(kPlayRate)});
  ASSERT_EQ(group.wait_exit("player", 90s), 0);
  ASSERT_NE(group.log("player").find(fmt::format("done: {0}/{0} scans sent", scans)), std::string::npos);

  // A played log's last keyframe closes once the robot has been silent a while: ask until every
  // scan is in the trajectory.
  const std::string tum = (dir / "played.tum").string();
  std::pair<int, std::string> run;
  ASSERT_TRUE(wait_until(
      [&] {
        run = ctl({"trajectory", kPlayedRobot, tum, "--format", "tum"});
        return run.first == 0 && run.second.find(fmt::format("wrote {} poses", scans)) != std::string::npos;
      },
      40s, 500ms))
      << run.second;

  const Trajectory played = read_tum(tum);
  auto relations = bench::read_relations(relations_file);
  ASSERT_TRUE(relations) << relations.message();
  const bench::RelationScore score =
      bench::score_relations(*relations, bench::StampedPoses(played.stamps, played.poses));
  // The raw odometry of the log, scored the same way, for comparison in the output.
  auto recorded = robot_log::read_carmen_log(log);
  ASSERT_TRUE(recorded) << recorded.message();
  Trajectory odometry;
  for (const robot_log::LaserScan& s : recorded->scans) {
    odometry.stamps.push_back(s.stamp_s);
    odometry.poses.push_back(s.odom);
  }
  const bench::RelationScore raw =
      bench::score_relations(*relations, bench::StampedPoses(odometry.stamps, odometry.poses));
  std::cout << relations->size() << " relations; played through the fleet: " << bench::describe(score)
            << "; raw odometry: " << bench::describe(raw) << "\n";

  EXPECT_EQ(score.missing, 0u) << "relations whose stamps the trajectory lacks";
  EXPECT_EQ(score.relations, relations->size());
  EXPECT_GE(relations->size(), 60u);  // one a second, plus the long ones
  EXPECT_LT(score.trans_abs.mean, kMaxMeanErrorM) << bench::describe(score);
  EXPECT_LT(score.rot_abs.mean, kMaxMeanErrorDeg) << bench::describe(score);
}

TEST(RecordLogFlag, TheSimulatorWritesEachRobotsLogAndRelations) {
  const TempDir dir("record-log");
  const DomainLease domain;
  ProcessGroup group;
  const int port = group.start_mosquitto();
  const std::string prefix = (dir / "run").string();
  group.start("simulator", {bin_path("slam-simulator"), "--domain", std::to_string(domain.id()), "--broker",
                            "tcp://127.0.0.1:" + std::to_string(port), "--robots", "2", "--world", "office",
                            "--random-walk", "--speed", "20", "--record-log", prefix});
  // About 40 simulated seconds: the logs are written as the simulation runs.
  const std::string first_log = prefix + "-sim-1.clf";
  ASSERT_TRUE(wait_until(
      [&] {
        std::error_code ec;
        return std::filesystem::file_size(first_log, ec) > 100'000 && !ec;
      },
      30s, 100ms))
      << group.log("simulator");
  group.stop("simulator");  // SIGTERM: the relations are written on the way out
  const std::string out = group.log("simulator");
  ASSERT_NE(out.find("recorded "), std::string::npos) << out;

  for (const char* robot : {"sim-1", "sim-2"}) {
    SCOPED_TRACE(robot);
    auto log = robot_log::read_carmen_log(prefix + "-" + robot + ".clf");
    ASSERT_TRUE(log) << log.message();
    EXPECT_EQ(log->stats.bad_lines, 0) << log->stats.first_bad;
    EXPECT_EQ(log->stats.comments, 3);
    ASSERT_GT(log->scans.size(), 300u);
    EXPECT_EQ(log->scans[0].ranges.size(), 16u);  // the default sensor, all around
    EXPECT_DOUBLE_EQ(log->scans[0].max_range_m, 4.0);
    auto relations = bench::read_relations(prefix + "-" + robot + ".relations");
    ASSERT_TRUE(relations) << relations.message();
    EXPECT_GT(relations->size(), 30u);
    // Every relation joins two of the log's scans: the odometry scores against it with nothing missing.
    std::vector<double> stamps;
    std::vector<Pose> poses;
    for (const robot_log::LaserScan& s : log->scans) {
      stamps.push_back(s.stamp_s);
      poses.push_back(s.odom);
    }
    const bench::RelationScore odometry =
        bench::score_relations(*relations, bench::StampedPoses(stamps, poses));
    EXPECT_EQ(odometry.missing, 0u);
    EXPECT_EQ(odometry.relations, relations->size());
    EXPECT_LT(odometry.trans_abs.mean, 0.5) << bench::describe(odometry);  // drift, not nonsense
  }
}

}  // namespace
}  // namespace slam::testkit
