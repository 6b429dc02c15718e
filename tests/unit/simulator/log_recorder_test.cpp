// --record-log's files: a simulated drive written as one CARMEN log and one relation file per robot,
// read back with the log player's reader (every report a scan, the odometry pose and the stamp as
// reported) and the relations' stamps exactly the log's, their motions the truth's; a missing
// directory and writing after the end are errors.
#include "simulator/core/log_recorder.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "simulator/core/builtin_worlds.hpp"
#include "simulator/core/carmen_writer.hpp"
#include "simulator/core/simulation.hpp"
#include "simulator/robot_log/carmen_log.hpp"
#include "temp_dir.hpp"

namespace slam::sim {
namespace {

using ::testing::HasSubstr;

struct RelationLine {
  std::string t1, t2;  // as written
  Pose motion;
};

std::vector<RelationLine> read_relation_lines(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::vector<RelationLine> out;
  for (std::string line; std::getline(in, line);) {
    std::istringstream fields(line);
    RelationLine r;
    double z = 0, roll = 0, pitch = 0;
    fields >> r.t1 >> r.t2 >> r.motion.x >> r.motion.y >> z >> roll >> pitch >> r.motion.theta;
    EXPECT_TRUE(fields && z == 0 && roll == 0 && pitch == 0) << line;
    out.push_back(r);
  }
  return out;
}

// Two robots random-walking the office for `seconds`, every report recorded; the reports are kept.
std::vector<RobotReport> drive(LogRecorder& recorder, double seconds) {
  SimulationConfig config;
  config.random_walk = true;
  config.seed = 7;
  auto sim = Simulation::create(std::move(*builtin_world("office")), config);
  EXPECT_TRUE(sim) << sim.message();
  EXPECT_TRUE(sim->spawn_random(2));
  std::vector<RobotReport> reports;
  while (sim->time() < seconds)
    for (const RobotReport& r : sim->step()) {
      EXPECT_TRUE(recorder.add(r));
      reports.push_back(r);
    }
  return reports;
}

TEST(LogRecorder, ASimulatedDriveReadsBackAsItsReportsAndTruth) {
  const testkit::TempDir dir("log-recorder");
  auto recorder = LogRecorder::create((dir / "office").string(), "office");
  ASSERT_TRUE(recorder) << recorder.message();
  const std::vector<RobotReport> reports = drive(*recorder, 45.0);
  ASSERT_TRUE(recorder->finish());
  EXPECT_EQ(recorder->robots(), 2u);
  EXPECT_EQ(recorder->scans(), static_cast<int64_t>(reports.size()));

  std::map<std::string, std::vector<const RobotReport*>> by_robot;
  for (const RobotReport& r : reports) by_robot[r.robot_id].push_back(&r);
  ASSERT_EQ(by_robot.size(), 2u);
  int64_t relations = 0;
  for (const auto& [id, sent] : by_robot) {
    SCOPED_TRACE(id);
    EXPECT_EQ(recorder->log_path(id), dir / ("office-" + id + ".clf"));
    auto log = robot_log::read_carmen_log(recorder->log_path(id));
    ASSERT_TRUE(log) << log.message();
    EXPECT_EQ(log->stats.bad_lines, 0) << log->stats.first_bad;
    ASSERT_EQ(log->scans.size(), sent.size());
    std::map<std::string, Pose> truth_at;  // by stamp as written
    for (size_t i = 0; i < sent.size(); ++i) {
      const robot_log::LaserScan& scan = log->scans[i];
      EXPECT_NEAR(scan.stamp_s, sent[i]->time_s, 1e-6);
      EXPECT_NEAR(scan.odom.x, sent[i]->reported_pose.x, 1e-6);
      EXPECT_NEAR(scan.odom.y, sent[i]->reported_pose.y, 1e-6);
      EXPECT_EQ(scan.ranges.size(), sent[i]->ranges.size());
      truth_at[stamp_text(sent[i]->time_s)] = sent[i]->true_pose;
    }

    const auto lines = read_relation_lines(recorder->relations_path(id));
    // 45 s: about 44 short relations and long ones from the first anchor's 0 and 10 s.
    EXPECT_GE(lines.size(), 44u);
    std::set<std::string> long_starts;
    for (const RelationLine& r : lines) {
      SCOPED_TRACE(r.t1 + " " + r.t2);
      ASSERT_TRUE(truth_at.contains(r.t1) && truth_at.contains(r.t2));  // the log's stamps, exactly
      const Pose motion = truth_at[r.t1].inverse().compose(truth_at[r.t2]);
      EXPECT_NEAR(r.motion.x, motion.x, 2e-6);
      EXPECT_NEAR(r.motion.y, motion.y, 2e-6);
      EXPECT_NEAR(wrap_angle(r.motion.theta - motion.theta), 0.0, 1e-8);
      if (std::stod(r.t2) - std::stod(r.t1) > 20) long_starts.insert(r.t1);
    }
    EXPECT_EQ(long_starts.size(), 2u);
    relations += static_cast<int64_t>(lines.size());
  }
  EXPECT_EQ(recorder->relations(), relations);

  EXPECT_THAT(recorder->add(reports.front()).message(), HasSubstr("finished"));
}

TEST(LogRecorder, AMissingDirectoryIsRefusedUpFront) {
  const testkit::TempDir dir("log-recorder");
  auto recorder = LogRecorder::create((dir / "nowhere" / "run").string(), "office");
  ASSERT_FALSE(recorder);
  EXPECT_THAT(recorder.message(), HasSubstr("does not exist"));
  EXPECT_FALSE(LogRecorder::create("", "office"));
  RelationPlan bad;
  bad.step_s = -1;
  EXPECT_THAT(LogRecorder::create((dir / "run").string(), "office", bad).message(), HasSubstr("step_s"));
}

}  // namespace
}  // namespace slam::sim
