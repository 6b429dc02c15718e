// Every slamctl subcommand, through the command line only, against a running fleet (mosquitto,
// gateway, mapper, planner, simulator): exit 0 and the expected output or effect seen on DDS, and a
// failing case per subcommand that exits non-zero with one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/fastdds/fast_topics.hpp"
#include "fastdds_inbox.hpp"
#include "process_group.hpp"

namespace slam::testkit {
namespace {

// One slamctl invocation: exit code and output (stdout and stderr).
struct CtlRun {
  int code = -1;
  std::string output;
  size_t lines() const { return static_cast<size_t>(std::count(output.begin(), output.end(), '\n')); }
};

// What slamctl's commands change, seen on DDS: ground truth and the grid layout.
class Effects {
 public:
  explicit Effects(int domain) {
    auto p = dds::Participant::create(domain, "slamctl-test");
    if (!p) throw std::runtime_error(p.message());
    participant_ = std::move(*p);
    truth_reader_ = make_inbox_reader(*participant_, dds::kSimGroundTruth, truths_);
    snapshot_reader_ = make_inbox_reader(*participant_, dds::kGridSnapshot, snapshots_);
  }
  std::optional<SimGroundTruth> truth() const { return truths_.last(any); }
  // The latest snapshot's resolution; 0 before any snapshot.
  double resolution() const {
    const auto latest = snapshots_.last(any);
    return latest ? latest->info().resolution() : 0.0;
  }

 private:
  static constexpr auto any = [](const auto&) { return true; };

  Inbox<SimGroundTruth> truths_;
  Inbox<GridSnapshot> snapshots_;
  std::unique_ptr<dds::Participant> participant_;
  std::unique_ptr<dds::Reader<SimGroundTruth>> truth_reader_;
  std::unique_ptr<dds::Reader<GridSnapshot>> snapshot_reader_;
};

class SlamctlTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string d = std::to_string(domain.id());
    const std::string broker = "tcp://127.0.0.1:" + std::to_string(port);
    group.start("gateway", {bin_path("slam-gateway"), "--domain", d, "--broker", broker});
    // SLAM off: the empty world gives a handful of far points, nothing a correction can lock on to;
    // this fixture is about slamctl (slam_test covers `slamctl pose` with correction on).
    group.start("mapper", {bin_path("slam-mapper"), "--domain", d, "--store", group.dir() + "/map.db",
                           "--slam", "off"});
    group.start("planner",
                {bin_path("slam-planner"), "--domain", d, "--goal-store", group.dir() + "/goals.json"});
    group.start("simulator", {bin_path("slam-simulator"), "--domain", d, "--broker", broker, "--world",
                              "empty", "--robots", "2", "--seed", "5"});
    ASSERT_TRUE(wait_until([&] { return robot_count() == 2; }, 30s)) << group.log("simulator");
    ASSERT_TRUE(wait_until([&] { return effects.resolution() > 0.0; }, 30s)) << group.log("mapper");
  }
  void TearDown() override {
    if (!HasFailure()) return;
    for (const char* s : {"gateway", "mapper", "planner", "simulator"})
      std::cerr << s << " log:\n" << group.log(s) << "\n";
  }

  CtlRun ctl(std::vector<std::string> args, int domain_id = -1) {
    const std::string name = "slamctl" + std::to_string(++runs);
    std::vector<std::string> argv{bin_path("slamctl"), "--domain",
                                  std::to_string(domain_id < 0 ? domain.id() : domain_id), "--timeout", "10"};
    argv.insert(argv.end(), args.begin(), args.end());
    group.start(name, argv);
    CtlRun r;
    r.code = group.wait_exit(name, 60s);
    r.output = group.log(name);
    return r;
  }
  // Exits non-zero with one line of explanation.
  void expect_fails(const std::vector<std::string>& args, int domain_id = -1) {
    const CtlRun r = ctl(args, domain_id);
    EXPECT_NE(r.code, 0) << args.front() << ": " << r.output;
    EXPECT_EQ(r.lines(), 1u) << args.front() << ": " << r.output;
  }
  void expect_ok(const CtlRun& r, const std::string& what) {
    EXPECT_EQ(r.code, 0) << what << ":\n" << r.output;
  }
  size_t robot_count() {
    const auto t = effects.truth();
    return t ? t->robots().size() : 0;
  }
  std::vector<std::string> robot_ids() {
    std::vector<std::string> ids;
    if (const auto t = effects.truth())
      for (const auto& r : t->robots()) ids.push_back(r.robot_id().to_string());
    return ids;
  }
  // The command `args` was answered by the mapper with MAP_OK: slamctl resends the request until the
  // mapper's reply arrives, exits 0 only on MAP_OK and prints the reply's message as its one line.
  // (A reader of MapReply in the test would race the reply: its writer may not have matched it yet.)
  void expect_map_ok(const std::vector<std::string>& args) {
    const CtlRun r = ctl(args);
    expect_ok(r, args.front());
    EXPECT_EQ(r.lines(), 1u) << args.front() << ": " << r.output;
  }

  DomainLease domain;
  DomainLease empty_domain;  // nothing runs here: commands find no service
  ProcessGroup group;
  int port = group.start_mosquitto();
  Effects effects{domain.id()};
  int runs = 0;
};

TEST_F(SlamctlTest, StatusRobotsAndEcho) {
  const CtlRun status = ctl({"status"});
  expect_ok(status, "status");
  for (const char* s : {"gateway", "mapper", "planner", "simulator"})
    EXPECT_NE(status.output.find(s), std::string::npos) << s << " missing:\n" << status.output;
  expect_fails({"status"}, empty_domain.id());

  // The gateway lists robots once their first messages went through.
  const std::vector<std::string> ids = robot_ids();
  ASSERT_EQ(ids.size(), 2u);
  CtlRun robots;
  ASSERT_TRUE(wait_until(
      [&] {
        robots = ctl({"robots"});
        return robots.code == 0 && robots.output.find(ids[0]) != std::string::npos &&
               robots.output.find(ids[1]) != std::string::npos;
      },
      30s, 500ms))
      << robots.output;
  EXPECT_EQ(robots.lines(), 2u) << robots.output;
  EXPECT_NE(robots.output.find(" correction "), std::string::npos) << robots.output;
  expect_fails({"robots"}, empty_domain.id());

  const CtlRun echo = ctl({"echo", "slam/sim/ground_truth", "-n", "1"});
  expect_ok(echo, "echo");
  EXPECT_EQ(echo.lines(), 1u) << echo.output;
  expect_fails({"echo", "slam/no/such/topic", "-n", "1"});
}

// The scripting and operator views: status in full and as JSON, robots as JSON, alerts, forget.
TEST_F(SlamctlTest, StatusVariantsAlertsAndForget) {
  const CtlRun verbose = ctl({"status", "--verbose"});
  expect_ok(verbose, "status --verbose");
  EXPECT_NE(verbose.output.find("waypoints_sent"), std::string::npos) << verbose.output;
  EXPECT_GT(verbose.lines(), 20u) << "every counter on a line: " << verbose.output;

  const CtlRun status = ctl({"status", "--json"});
  expect_ok(status, "status --json");
  std::set<std::string> services;
  for (const auto& s : nlohmann::json::parse(status.output)) {
    services.insert(s["service"].get<std::string>());
    EXPECT_TRUE(s["counters"].is_object()) << s.dump();
  }
  for (const char* s : {"gateway", "mapper", "planner", "simulator"}) EXPECT_TRUE(services.contains(s)) << s;

  CtlRun robots;
  ASSERT_TRUE(wait_until(
      [&] {
        robots = ctl({"robots", "--json"});
        return robots.code == 0 && nlohmann::json::parse(robots.output).size() == 2;
      },
      30s, 500ms))
      << robots.output;
  for (const auto& r : nlohmann::json::parse(robots.output)) EXPECT_EQ(r["presence"], "online") << r.dump();

  const CtlRun alerts = ctl({"alerts"});
  expect_ok(alerts, "alerts");
  EXPECT_GE(alerts.lines(), 1u) << alerts.output;
  const CtlRun alerts_json = ctl({"alerts", "--all", "--json"});
  expect_ok(alerts_json, "alerts --json");
  EXPECT_TRUE(nlohmann::json::parse(alerts_json.output).is_array()) << alerts_json.output;
  expect_fails({"alerts"}, empty_domain.id());

  // A simulated robot keeps reporting, so it comes back at once: this is about the command.
  const CtlRun forget = ctl({"forget", robot_ids().at(0)});
  expect_ok(forget, "forget");
  EXPECT_EQ(forget.lines(), 1u) << forget.output;
  EXPECT_NE(forget.output.find("forgotten"), std::string::npos) << forget.output;
  expect_fails({"forget"});
  expect_fails({"forget", "r1"}, empty_domain.id());
}

TEST_F(SlamctlTest, GoalAndPath) {
  const std::string id = robot_ids().at(0);
  const CtlRun goal = ctl({"goal", id, "direct", "5", "5"});
  expect_ok(goal, "goal");
  EXPECT_NE(goal.output.find("goal direct sent to " + id), std::string::npos) << goal.output;
  // The planner takes the goal: the robot's row shows its mode.
  CtlRun robots;
  EXPECT_TRUE(wait_until(
      [&] {
        robots = ctl({"robots"});
        std::istringstream lines(robots.output);
        for (std::string line; std::getline(lines, line);)
          if (line.find(id) != std::string::npos && line.find("direct/") != std::string::npos) return true;
        return false;
      },
      30s, 500ms))
      << robots.output;
  expect_fails({"goal", id, "fly"});

  // Between the two robots: both stand in space the mapper has seen.
  const auto truth = effects.truth();
  ASSERT_TRUE(truth);
  const auto& a = truth->robots()[0].true_pose();
  const auto& b = truth->robots()[1].true_pose();
  CtlRun path;
  EXPECT_TRUE(wait_until(
      [&] {
        path = ctl({"path", std::to_string(a.x()), std::to_string(a.y()), std::to_string(b.x()),
                    std::to_string(b.y())});
        return path.code == 0;
      },
      30s, 1s))
      << path.output;
  EXPECT_FALSE(path.output.empty());
  const CtlRun outside = ctl({"path", "0", "0", "900", "900"});
  EXPECT_NE(outside.code, 0) << outside.output;
  expect_fails({"path", "1", "2", "3"});
}

TEST_F(SlamctlTest, MissionAndMissions) {
  const std::string id = robot_ids().at(0);
  const auto truth = effects.truth();
  ASSERT_TRUE(truth);
  const auto& at = truth->robots()[0].true_pose();
  const auto coord = [](double v) { return std::to_string(v); };
  // A small patrol around where the robot stands (space the mapper has seen).
  const CtlRun sent =
      ctl({"mission", id, coord(at.x() + 0.5), coord(at.y()), coord(at.x()), coord(at.y() + 0.5), "--loop"});
  expect_ok(sent, "mission");
  EXPECT_EQ(sent.lines(), 1u) << sent.output;
  EXPECT_NE(sent.output.find("mission of 2 waypoint(s), looped, sent to " + id), std::string::npos)
      << sent.output;
  // slamctl exits once the planner acknowledged it: what `missions` lists is the planner's report of
  // the mission (active, or failed when the empty world left the waypoints unexplored).
  CtlRun listed;
  EXPECT_TRUE(wait_until(
      [&] {
        listed = ctl({"missions"});
        return listed.code == 0 && listed.output.find(id + " mission ") != std::string::npos &&
               listed.output.find(", waypoint ") != std::string::npos;
      },
      30s, 500ms))
      << listed.output;

  // From a mission file, once: it replaces the patrol.
  const std::string file = group.dir() + "/mission.yaml";
  std::ofstream(file) << "waypoints:\n  - [" << at.x() << ", " << at.y() << "]\n";
  const CtlRun from_file = ctl({"mission", id, "--file", file});
  expect_ok(from_file, "mission --file");
  EXPECT_NE(from_file.output.find("mission of 1 waypoint(s) sent to " + id), std::string::npos)
      << from_file.output;
  expect_fails({"mission", id, "1", "2", "3"});
  expect_fails({"mission", id, "1", "2", "--loop"});
  expect_fails({"mission", id, "--file", group.dir() + "/no-such-file.yaml"});
  expect_fails({"missions"}, empty_domain.id());
}

TEST_F(SlamctlTest, MapFilesGridAndEdits) {
  const std::string yaml = group.dir() + "/saved.yaml";
  expect_map_ok({"map", "save", yaml});
  EXPECT_TRUE(std::filesystem::exists(yaml));
  expect_map_ok({"map", "load", yaml});
  expect_fails({"map", "load", group.dir() + "/missing.yaml"});

  const CtlRun grid = ctl({"grid", "--resolution", "0.1"});
  expect_ok(grid, "grid");
  EXPECT_EQ(grid.lines(), 1u) << grid.output;
  EXPECT_NE(grid.output.find("grid"), std::string::npos) << grid.output;
  EXPECT_TRUE(wait_until([&] { return std::abs(effects.resolution() - 0.1) < 1e-9; }, 20s))
      << "resolution " << effects.resolution();
  expect_fails({"grid", "--resolution", "-1"});

  expect_map_ok({"obstruct", "3", "3"});
  expect_fails({"obstruct", "3"});
  expect_map_ok({"unobstruct", "3", "3"});
  expect_fails({"unobstruct"});
  expect_map_ok({"reset", robot_ids().at(0)});
  expect_fails({"reset"});
}

TEST_F(SlamctlTest, SimSpawnRemovePauseResume) {
  const CtlRun spawn = ctl({"sim", "spawn", "2"});
  expect_ok(spawn, "sim spawn");
  EXPECT_EQ(spawn.lines(), 1u) << spawn.output;
  EXPECT_NE(spawn.output.find("spawned 2"), std::string::npos) << spawn.output;
  EXPECT_TRUE(wait_until([&] { return robot_count() == 4; }, 20s)) << robot_count();
  expect_fails({"sim", "spawn", "0"});

  const std::string gone = robot_ids().at(0);
  expect_ok(ctl({"sim", "remove", gone}), "sim remove");
  EXPECT_TRUE(wait_until(
      [&] {
        const auto ids = robot_ids();
        return ids.size() == 3 && std::find(ids.begin(), ids.end(), gone) == ids.end();
      },
      20s));
  expect_fails({"sim", "remove"});

  expect_ok(ctl({"sim", "pause"}), "sim pause");
  EXPECT_TRUE(wait_until([&] { return effects.truth() && effects.truth()->paused(); }, 20s));
  expect_ok(ctl({"sim", "resume"}), "sim resume");
  EXPECT_TRUE(wait_until([&] { return effects.truth() && !effects.truth()->paused(); }, 20s));
  expect_fails({"sim", "pause"}, empty_domain.id());
}

// `slamctl pose` without a fleet: the arguments are checked before DDS is touched, and with no
// mapper to answer the command says so on one line and exits 1.
TEST(SlamctlPoseTest, ValidatesArgumentsAndTimesOutWithoutAMapper) {
  DomainLease nothing_runs;
  ProcessGroup group;
  const auto run = [&](const std::string& name, std::vector<std::string> args) {
    std::vector<std::string> argv{bin_path("slamctl"), "--domain", std::to_string(nothing_runs.id()),
                                  "--timeout",         "1",        "pose"};
    argv.insert(argv.end(), args.begin(), args.end());
    group.start(name, argv);
    CtlRun r;
    r.code = group.wait_exit(name, 30s);
    r.output = group.log(name);
    return r;
  };

  const CtlRun help = run("help", {"--help"});
  EXPECT_EQ(help.code, 0) << help.output;
  EXPECT_NE(help.output.find("THETA"), std::string::npos) << help.output;

  for (const auto& [name, args] :
       std::vector<std::pair<std::string, std::vector<std::string>>>{{"nan", {"r1", "nan", "2", "90"}},
                                                                     {"inf", {"r1", "1", "2", "inf"}},
                                                                     {"word", {"r1", "1", "y", "90"}},
                                                                     {"missing", {"r1", "1", "2"}}}) {
    const CtlRun bad = run(name, args);
    EXPECT_EQ(bad.code, 2) << name << ": " << bad.output;
    EXPECT_EQ(bad.lines(), 1u) << name << ": " << bad.output;
  }

  const CtlRun unanswered = run("unanswered", {"r1", "1.5", "-2", "90"});
  EXPECT_EQ(unanswered.code, 1) << unanswered.output;
  EXPECT_EQ(unanswered.lines(), 1u) << unanswered.output;
  EXPECT_NE(unanswered.output.find("mapper"), std::string::npos) << unanswered.output;
}

}  // namespace
}  // namespace slam::testkit
