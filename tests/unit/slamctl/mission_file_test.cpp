// slamctl mission: waypoints from numbers and from a mission file, and the progress line.
#include "slamctl/mission_file.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "temp_dir.hpp"

namespace slam::ctl {
namespace {

std::string error_of(std::string_view yaml) {
  auto r = parse_mission_file(yaml);
  return r ? std::string("accepted") : r.message();
}

TEST(MissionWaypoints, NumbersArePairs) {
  auto wps = waypoints_from_numbers({1, 2, -3.5, 4});
  ASSERT_TRUE(wps) << wps.message();
  ASSERT_EQ(wps->size(), 2u);
  EXPECT_EQ((*wps)[1].x(), -3.5);
  EXPECT_EQ((*wps)[1].y(), 4.0);
  EXPECT_FALSE(waypoints_from_numbers({1, 2, 3}));
  EXPECT_FALSE(waypoints_from_numbers({}));
  EXPECT_FALSE(waypoints_from_numbers({1, NAN}));
  EXPECT_FALSE(waypoints_from_numbers(std::vector<double>(2 * 257, 1.0)));
}

TEST(MissionFile, ReadsWaypointsAndLoop) {
  auto spec = parse_mission_file("# office patrol\nloop: true\nwaypoints:\n  - [1.0, 2]\n  - [-4.5, 2.25]\n");
  ASSERT_TRUE(spec) << spec.message();
  EXPECT_TRUE(spec->loop);
  ASSERT_EQ(spec->waypoints.size(), 2u);
  EXPECT_EQ(spec->waypoints[0].y(), 2.0);
  EXPECT_EQ(spec->waypoints[1].x(), -4.5);
  auto once = parse_mission_file("waypoints: [[0, 0]]");
  ASSERT_TRUE(once) << once.message();
  EXPECT_FALSE(once->loop);
}

TEST(MissionFile, BadFilesNameWhatIsWrong) {
  EXPECT_NE(error_of("waypoints: [[0, 0]").find("not valid YAML"), std::string::npos);
  EXPECT_NE(error_of("- [0, 0]").find("must be a map"), std::string::npos);
  EXPECT_EQ(error_of("loop: true"), "\"waypoints\" must be a list of [x, y]");
  EXPECT_EQ(error_of("waypoints: []"), "a mission needs at least one waypoint");
  EXPECT_EQ(error_of("waypoints: [[0, 0], [1]]"), "waypoints[1] must be [x, y] in metres");
  EXPECT_EQ(error_of("waypoints: [[0, zero]]"), "waypoints[0] must be [x, y] in metres");
  EXPECT_EQ(error_of("waypoints: [[0, .nan]]"), "waypoints[0] is not finite");
  EXPECT_EQ(error_of("waypoints: [[0, 0]]\nloop: often"), "\"loop\" must be true or false");
  EXPECT_EQ(error_of("waypoints: [[0, 0]]\nrepeat: 3"), "unknown key \"repeat\" (waypoints, loop)");
}

TEST(MissionFile, LoadNamesThePath) {
  testkit::TempDir dir("mission-file");
  const std::string path = (dir.path() / "patrol.yaml").string();
  EXPECT_NE(load_mission_file(path).message().find(path + ": cannot be read"), std::string::npos);
  std::ofstream(path) << "waypoints: [[1, 1], [2, 2]]\nloop: yes\n";
  auto spec = load_mission_file(path);
  ASSERT_TRUE(spec) << spec.message();
  EXPECT_TRUE(spec->loop);
  std::ofstream(path) << "waypoints: 3\n";
  EXPECT_NE(load_mission_file(path).message().find(path + ": \"waypoints\""), std::string::npos);
}

TEST(MissionLine, ShowsTheWaypointBeingDrivenToAndTheLaps) {
  NavMission m;
  m.robot_id("r7");
  m.mission_id(12);
  std::vector<Point2> wps(3);
  wps[1].x(1.5);
  wps[1].y(-2);
  m.waypoints(wps);
  m.loop(true);
  m.current(1);
  m.laps(4);
  m.status(MISSION_ACTIVE);
  m.reason("waypoint 0 skipped: NO_PATH");
  EXPECT_EQ(format_mission(m),
            "r7 mission 12: active, waypoint 2/3 (1.50, -2.00), 4 lap(s) done, looped; waypoint 0 skipped: "
            "NO_PATH\n");
}

}  // namespace
}  // namespace slam::ctl
