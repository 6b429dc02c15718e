// slam-viewer black-box: started headless under xvfb-run on its own DDS domain, it is sent a known
// grid, two robots with observations and a path; its screenshot must show the robots' colours
// where their points are, occupied cells dark and free cells light; synthetic clicks must publish
// a NavGoal and a MapEdit at the world points under the clicked pixels. Run with --snapshot-dir it
// keeps going, fits itself to data that arrives after it started, and writes a numbered PNG plus
// latest.png every period.
#include <gtest/gtest.h>
#include <unistd.h>

#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <regex>
#include <sstream>
#include <string>
#include <tuple>

#include "common/fastdds/fast_topics.hpp"
#include "observation_batches.hpp"
#include "process_group.hpp"
#include "viewer/core/cell_colors.hpp"
#include "viewer/core/view_transform.hpp"

namespace slam {
namespace {

using namespace testkit;
using viewer::Rgba;
using viewer::ViewTransform;

// The grid: 10 x 8 m at 0.1 m, origin (-5, -4); x >= 2 m occupied, y >= 3 m unknown, rest free.
constexpr uint32_t kW = 100, kH = 80;
constexpr double kRes = 0.1, kOx = -5.0, kOy = -4.0;

GridSnapshot make_grid() {
  GridSnapshot s;
  s.layout_id(3);
  s.version(1);
  GridInfo info;
  info.width(kW);
  info.height(kH);
  info.resolution(kRes);
  Point2 o;
  o.x(kOx);
  o.y(kOy);
  info.origin(o);
  info.inflation_radius(0.0);
  s.info(info);
  std::vector<uint8_t> cells(size_t{kW} * kH);
  for (uint32_t y = 0; y < kH; ++y)
    for (uint32_t x = 0; x < kW; ++x) cells[size_t{y} * kW + x] = x >= 70 ? 2 : (y >= 70 ? 0 : 1);
  s.cells(cells);
  return s;
}

Pose2 pose(double x, double y, double theta) {
  Pose2 p;
  p.x(x);
  p.y(y);
  p.theta(theta);
  return p;
}

Point2 pt(double x, double y) {
  Point2 p;
  p.x(x);
  p.y(y);
  return p;
}

RobotState state(const std::string& id, Pose2 p) {
  RobotState s;
  s.robot_id(id);
  s.presence(PRESENCE_ONLINE);
  s.pose(p);
  s.has_heading(true);
  s.battery(-1.0f);
  return s;
}

// A dense 0.6 m square of hits around (cx, cy), so it renders as solid colour.
RobotObservation observation(const std::string& id, Pose2 p, double cx, double cy) {
  RobotObservation o;
  o.robot_id(id);
  o.seq(1);
  o.pose(p);
  o.has_heading(true);
  for (int i = 0; i <= 20; ++i)
    for (int j = 0; j <= 20; ++j) o.hits().push_back(pt(cx - 0.3 + 0.03 * i, cy - 0.3 + 0.03 * j));
  return o;
}

bool have_xvfb() {
  return ::access("/usr/bin/xvfb-run", X_OK) == 0 && ::access("/usr/bin/Xvfb", X_OK) == 0;
}

// Starts Xvfb as "xvfb" in `group` (its own process, so the viewer can be stopped alone, as
// compose/launch.sh does) and returns its DISPLAY, or "" when it did not come up. -displayfd 1
// makes the server pick a free display and print its number into the log.
std::string start_xvfb(ProcessGroup& group) {
  group.start("xvfb", {"Xvfb", "-displayfd", "1", "-screen", "0", "1280x800x24", "-nolisten", "tcp"});
  const std::regex number("(^|\\n)([0-9]+)\\n");
  std::smatch m;
  std::string log;
  if (!wait_until(
          [&] {
            log = group.log("xvfb");
            return std::regex_search(log, m, number);
          },
          20s))
    return "";
  std::string display = m[2].str();
  return display.insert(0, 1, ':');
}

struct Image {
  int w = 0, h = 0;
  std::vector<unsigned char> rgb;
  // Pixel at the window point of world `p`.
  Rgba at(const ViewTransform& v, Vec2 world) const {
    const Vec2 s = v.world_to_screen(world);
    const int x = static_cast<int>(std::lround(s.x)), y = static_cast<int>(std::lround(s.y));
    if (x < 0 || y < 0 || x >= w || y >= h) return {-1, -1, -1, -1};
    const unsigned char* px =
        &rgb[(static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)) * 3];
    return {px[0] / 255.0f, px[1] / 255.0f, px[2] / 255.0f, 1.0f};
  }
};

// The PNG at `path`, or an image of width 0.
Image load_png(const std::string& path) {
  Image img;
  int channels = 0;
  unsigned char* data = stbi_load(path.c_str(), &img.w, &img.h, &channels, 3);
  if (!data) return {};
  img.rgb.assign(data, data + static_cast<size_t>(img.w) * static_cast<size_t>(img.h) * 3);
  stbi_image_free(data);
  return img;
}

// The last "view center=..." line in a log (every automatic fit and the screenshot log one).
Result<ViewTransform> last_view(const std::string& log) {
  const auto at = log.rfind("view center=");
  if (at == std::string::npos) return Error{"no view line in the log"};
  return ViewTransform::parse(log.substr(at, log.find('\n', at) - at));
}

float brightness(const Rgba& c) {
  return (c.r + c.g + c.b) / 3.0f;
}
// `tolerance` per channel; path and target strokes are drawn at 90 % alpha and antialiased.
bool close_to(const Rgba& a, const Rgba& b, float tolerance = 0.08f) {
  return std::abs(a.r - b.r) < tolerance && std::abs(a.g - b.g) < tolerance &&
         std::abs(a.b - b.b) < tolerance;
}
// The pixel `dx`, `dy` screen pixels away from world point `world`.
Rgba pixel_off(const Image& img, const ViewTransform& v, Vec2 world, double dx, double dy) {
  const Vec2 s = v.world_to_screen(world);
  return img.at(v, v.screen_to_world({s.x + dx, s.y + dy}));
}
std::string str(const Rgba& c) {
  std::ostringstream s;
  s << "(" << c.r << ", " << c.g << ", " << c.b << ")";
  return s.str();
}

TEST(ViewerTest, RendersGridRobotsAndPointsAndSendsClicks) {
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed";
  DomainLease domain;
  auto participant = dds::Participant::create(domain.id(), "viewer_test");
  ASSERT_TRUE(participant) << participant.message();
  auto& p = **participant;
  auto grid_w = dds::make_writer(p, dds::kGridSnapshot);
  auto state_w = dds::make_writer(p, dds::kRobotState);
  auto obs_w = dds::make_writer(p, dds::kRobotObservations);
  auto path_w = dds::make_writer(p, dds::kRobotPath);
  auto goal_r = dds::make_reader(p, dds::kNavGoal);
  auto edit_r = dds::make_reader(p, dds::kMapEdit);
  ASSERT_TRUE(grid_w && state_w && obs_w && path_w && goal_r && edit_r);

  ProcessGroup group;
  const std::string png = group.dir() + "/viewer.png";
  group.start("viewer", {"xvfb-run",
                         "-a",
                         "-s",
                         "-screen 0 1280x800x24",
                         bin_path("slam-viewer"),
                         "--domain",
                         std::to_string(domain.id()),
                         "--width",
                         "1280",
                         "--height",
                         "800",
                         "--screenshot",
                         png,
                         "--frames",
                         "20",
                         "--wait-map",
                         "--wait-robots",
                         "2",
                         "--max-wait",
                         "60",
                         "--click",
                         "900,420,left@3",
                         "--click",
                         "1000,300,right@4"});
  ASSERT_TRUE(
      wait_until([&] { return (*obs_w)->matched_readers() > 0 && (*grid_w)->matched_readers() > 0; }, 60s))
      << group.log("viewer");

  // Delivery is checked through the screenshot, not through write()'s result.
  (*grid_w)->write(make_grid());
  const Pose2 a = pose(-3.0, 2.0, 0.0), b = pose(-3.0, -2.5, M_PI / 2.0);
  (*state_w)->write(state("alpha", a));
  (*state_w)->write(state("bravo", b));
  (*obs_w)->write(testkit::batch_of(observation("alpha", a, -1.0, 1.0)));
  (*obs_w)->write(testkit::batch_of(observation("bravo", b, -1.0, -2.0)));
  RobotPath path;
  path.robot_id("alpha");
  path.goal_id(1);
  path.mode(GOAL_DIRECT);
  path.status(GOAL_STATUS_ACTIVE);
  path.target(pt(1.0, 2.0));
  path.waypoints({pt(0.0, 2.0), pt(1.0, 2.0)});
  (*path_w)->write(path);

  ASSERT_EQ(group.wait_exit("viewer", 90s), 0) << group.log("viewer");
  const std::string log = group.log("viewer");
  auto view = last_view(log);
  ASSERT_TRUE(view) << view.message() << "\n" << log;

  const Image img = load_png(png);
  ASSERT_EQ(img.w, 1280) << "cannot read " << png;
  ASSERT_EQ(img.h, 800);

  // Points in each robot's colour where they were observed; robots drawn at their poses.
  for (const auto& [id, where] :
       {std::pair<std::string, Vec2>{"alpha", {-1.0, 1.0}}, {"bravo", {-1.0, -2.0}}}) {
    const Rgba want = viewer::default_robot_color(id);
    EXPECT_TRUE(close_to(img.at(*view, where), want))
        << id << " points: got " << str(img.at(*view, where)) << " want " << str(want);
  }
  EXPECT_TRUE(close_to(img.at(*view, {-3.0, 2.0}), viewer::default_robot_color("alpha")))
      << "robot alpha: got " << str(img.at(*view, {-3.0, 2.0}));
  EXPECT_TRUE(close_to(img.at(*view, {-3.0, -2.5}), viewer::default_robot_color("bravo")))
      << "robot bravo: got " << str(img.at(*view, {-3.0, -2.5}));
  // Each robot is a triangle along its heading (alpha faces +x, bravo +y), opaque in its colour: its
  // nose reaches 0.6 of its length ahead of the pose, its base only 0.4 behind, and it is 0.7 wide.
  // The length is the default robot size (0.35 m) or 14 pixels, whichever is longer on screen.
  const double len = std::max(0.35, 14.0 / view->scale());
  for (const auto& [id, where, heading] : {std::tuple<std::string, Vec2, double>{"alpha", {-3.0, 2.0}, 0.0},
                                           {"bravo", {-3.0, -2.5}, M_PI / 2.0}}) {
    const Rgba want = viewer::default_robot_color(id);
    const Vec2 dir{std::cos(heading), std::sin(heading)}, side{-dir.y, dir.x};
    const auto along = [&](double fwd, double lateral) {
      return img.at(*view, {where.x + len * (fwd * dir.x + lateral * side.x),
                            where.y + len * (fwd * dir.y + lateral * side.y)});
    };
    EXPECT_TRUE(close_to(along(0.3, 0.0), want)) << id << " ahead: " << str(along(0.3, 0.0));
    EXPECT_TRUE(close_to(along(-0.3, 0.2), want)) << id << " beside its base: " << str(along(-0.3, 0.2));
    EXPECT_FALSE(close_to(along(-0.55, 0.0), want)) << id << " behind its base: " << str(along(-0.55, 0.0));
    // Off-centre: alpha's path continues straight ahead of it.
    EXPECT_FALSE(close_to(along(0.8, 0.25), want)) << id << " beyond its nose: " << str(along(0.8, 0.25));
    EXPECT_FALSE(close_to(along(0.0, 0.5), want)) << id << " beyond its side: " << str(along(0.0, 0.5));
  }
  // alpha's path: a line in its colour from the robot through the waypoints, and the active target
  // marker (a cross in a 9-pixel ring) at the target.
  const Rgba alpha_color = viewer::default_robot_color("alpha");
  for (const Vec2 on_path : {Vec2{-1.5, 2.0}, Vec2{0.5, 2.0}})
    EXPECT_TRUE(close_to(img.at(*view, on_path), alpha_color, 0.15f))
        << "path at (" << on_path.x << ", " << on_path.y << "): " << str(img.at(*view, on_path));
  EXPECT_FALSE(close_to(img.at(*view, {-1.5, 2.4}), alpha_color, 0.15f)) << "beside the path";
  const Vec2 target{1.0, 2.0};
  // The ring is a thin antialiased polygon: one pixel of a 3 x 3 patch on it must show it.
  bool ring = false;
  for (double dx = -1.0; dx <= 1.0; ++dx)
    for (double dy = -1.0; dy <= 1.0; ++dy)
      ring = ring || close_to(pixel_off(img, *view, target, 8.5 + dx, dy), alpha_color, 0.2f);
  EXPECT_TRUE(ring) << "target ring: " << str(pixel_off(img, *view, target, 8.5, 0.0));
  EXPECT_TRUE(close_to(pixel_off(img, *view, target, 5.0, 5.0), alpha_color, 0.2f))
      << "target cross: " << str(pixel_off(img, *view, target, 5.0, 5.0));
  EXPECT_FALSE(close_to(pixel_off(img, *view, target, 0.0, 5.5), alpha_color, 0.2f))
      << "inside the ring, off the cross: " << str(pixel_off(img, *view, target, 0.0, 5.5));

  // Occupied cells dark, free cells light, unknown in between.
  EXPECT_LT(brightness(img.at(*view, {3.5, -1.0})), 0.25f) << str(img.at(*view, {3.5, -1.0}));
  EXPECT_GT(brightness(img.at(*view, {0.5, -1.0})), 0.8f) << str(img.at(*view, {0.5, -1.0}));
  const float unknown = brightness(img.at(*view, {-2.0, 3.5}));
  EXPECT_GT(unknown, 0.3f);
  EXPECT_LT(unknown, 0.7f);

  // The left click set a target (NavGoal) and the right click obstructed a cell (MapEdit) at the
  // world points under those pixels.
  std::vector<NavGoal> goals;
  std::vector<MapEdit> edits;
  ASSERT_TRUE(wait_until([&] { return (*goal_r)->take(goals) + goals.size() > 0; }, 10s));
  ASSERT_TRUE(wait_until([&] { return (*edit_r)->take(edits) + edits.size() > 0; }, 10s));
  const Vec2 goal_at = view->screen_to_world({900.0, 420.0}),
             edit_at = view->screen_to_world({1000.0, 300.0});
  EXPECT_EQ(goals.back().robot_id().to_string(), "*");
  EXPECT_EQ(goals.back().mode(), GOAL_DIRECT);
  EXPECT_NEAR(goals.back().target().x(), goal_at.x, 1e-6);
  EXPECT_NEAR(goals.back().target().y(), goal_at.y, 1e-6);
  EXPECT_EQ(edits.back().kind(), EDIT_OBSTRUCT);
  EXPECT_NEAR(edits.back().point().x(), edit_at.x, 1e-6);
  EXPECT_NEAR(edits.back().point().y(), edit_at.y, 1e-6);
}

// Observations arrive raw (odometry frame): the viewer draws them through the robot's PoseCorrection.
// The pose tool's synthetic drags: one released (an InitialPose goes out), one held at the
// screenshot (its arrow is drawn).
TEST(ViewerTest, DrawsRawPointsThroughTheCorrectionAndSendsInitialPose) {
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed";
  DomainLease domain;
  auto participant = dds::Participant::create(domain.id(), "viewer_test");
  ASSERT_TRUE(participant) << participant.message();
  auto& p = **participant;
  auto grid_w = dds::make_writer(p, dds::kGridSnapshot);
  auto state_w = dds::make_writer(p, dds::kRobotState);
  auto obs_w = dds::make_writer(p, dds::kRobotObservations);
  auto correction_w = dds::make_writer(p, dds::kPoseCorrection);
  auto initial_r = dds::make_reader(p, dds::kInitialPose);
  ASSERT_TRUE(grid_w && state_w && obs_w && correction_w && initial_r);

  // map <- odom: a quarter turn and (1, -1): the raw square around (2, 1) lands around (0, 1).
  PoseCorrection c;
  c.robot_id("alpha");
  c.version(4);
  c.map_from_odom(pose(1.0, -1.0, M_PI / 2.0));
  c.keyframes(3);
  c.source(CORRECTION_LOOP);
  (*correction_w)->write(c);

  ProcessGroup group;
  const std::string png = group.dir() + "/viewer.png";
  group.start("viewer", {"xvfb-run",
                         "-a",
                         "-s",
                         "-screen 0 1280x800x24",
                         bin_path("slam-viewer"),
                         "--domain",
                         std::to_string(domain.id()),
                         "--width",
                         "1280",
                         "--height",
                         "800",
                         "--screenshot",
                         png,
                         "--frames",
                         "20",
                         "--wait-map",
                         "--wait-robots",
                         "1",
                         "--max-wait",
                         "60",
                         "--pose-drag",
                         "alpha:800,300>900,300@3-6",
                         "--pose-drag",
                         "alpha:1000,600>1000,500@10-100"});
  ASSERT_TRUE(
      wait_until([&] { return (*obs_w)->matched_readers() > 0 && (*grid_w)->matched_readers() > 0; }, 60s))
      << group.log("viewer");
  (*grid_w)->write(make_grid());
  (*state_w)->write(state("alpha", pose(-3.0, 2.0, 0.0)));
  (*obs_w)->write(testkit::batch_of(observation("alpha", pose(0.0, 0.0, 0.0), 2.0, 1.0)));

  ASSERT_EQ(group.wait_exit("viewer", 90s), 0) << group.log("viewer");
  const std::string log = group.log("viewer");
  auto view = last_view(log);
  ASSERT_TRUE(view) << view.message() << "\n" << log;
  const Image img = load_png(png);
  ASSERT_EQ(img.w, 1280) << "cannot read " << png;

  const Rgba alpha = viewer::default_robot_color("alpha");
  EXPECT_TRUE(close_to(img.at(*view, {0.0, 1.0}), alpha)) << "corrected: " << str(img.at(*view, {0.0, 1.0}));
  EXPECT_FALSE(close_to(img.at(*view, {2.0, 1.0}), alpha)) << "raw place: " << str(img.at(*view, {2.0, 1.0}));
  // The held drag's arrow: amber along the drag, between press and release.
  const Rgba amber{1.0f, 200.0f / 255.0f, 0.0f, 1.0f};
  const Vec2 mid = view->screen_to_world({1000.0, 550.0});
  EXPECT_TRUE(close_to(img.at(*view, mid), amber, 0.15f)) << "arrow: " << str(img.at(*view, mid));

  // The released drag: alpha is at the press point, heading along the drag (screen right = +x).
  std::vector<InitialPose> poses;
  ASSERT_TRUE(wait_until([&] { return (*initial_r)->take(poses) + poses.size() > 0; }, 10s)) << log;
  const Vec2 at = view->screen_to_world({800.0, 300.0});
  EXPECT_EQ(poses.front().robot_id().to_string(), "alpha");
  EXPECT_NEAR(poses.front().pose().x(), at.x, 1e-6);
  EXPECT_NEAR(poses.front().pose().y(), at.y, 1e-6);
  EXPECT_NEAR(poses.front().pose().theta(), 0.0, 1e-6);
}

TEST(ViewerTest, SnapshotsPeriodicallyAndFitsToDataThatArrivesLater) {
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed";
  DomainLease domain;
  auto participant = dds::Participant::create(domain.id(), "viewer_snapshot_test");
  ASSERT_TRUE(participant) << participant.message();
  auto& p = **participant;
  auto grid_w = dds::make_writer(p, dds::kGridSnapshot);
  auto state_w = dds::make_writer(p, dds::kRobotState);
  auto obs_w = dds::make_writer(p, dds::kRobotObservations);
  ASSERT_TRUE(grid_w && state_w && obs_w);

  ProcessGroup group;
  const std::filesystem::path dir = group.dir() + "/snapshots";
  const std::string display = start_xvfb(group);
  ASSERT_FALSE(display.empty()) << group.log("xvfb");
  group.start("viewer",
              {"env", "DISPLAY=" + display, bin_path("slam-viewer"), "--domain", std::to_string(domain.id()),
               "--snapshot-dir", dir.string(), "--snapshot-period", "1", "--fps", "20"});
  ASSERT_TRUE(
      wait_until([&] { return (*obs_w)->matched_readers() > 0 && (*grid_w)->matched_readers() > 0; }, 60s))
      << group.log("viewer");

  // Everything arrives after the viewer started: it must fit the view to it by itself.
  (*grid_w)->write(make_grid());
  const Pose2 a = pose(-3.0, 2.0, 0.0);
  (*state_w)->write(state("alpha", a));
  (*obs_w)->write(testkit::batch_of(observation("alpha", a, -1.0, 1.0)));

  // The second snapshot taken with the data in (the log lines name them): by then the view has
  // held still long enough for the point texture to be complete.
  const std::regex with_data(
      "snapshot (\\S+) written \\(1280x800, [^)]*1/1 robots online, 441 points, map 100x80");
  std::vector<std::string> shots;
  std::string log;
  ASSERT_TRUE(wait_until(
      [&] {
        log = group.log("viewer");
        shots.clear();
        for (std::sregex_iterator it(log.begin(), log.end(), with_data), end; it != end; ++it)
          shots.push_back((*it)[1]);
        return shots.size() >= 2;
      },
      60s))
      << log;
  const std::string shot = shots[1];
  ASSERT_TRUE(wait_until([&] { return std::filesystem::exists(dir / "snapshot-0002.png"); }, 30s)) << log;

  // Ctrl-C: a clean exit (the X server is still up).
  group.stop("viewer", SIGINT);
  EXPECT_EQ(group.wait_exit("viewer", 15s), 0) << group.log("viewer");
  log = group.log("viewer");

  // Every file is a complete PNG of the window; no temp file is left; latest is the newest.
  size_t numbered = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    EXPECT_EQ(name.find(".tmp"), std::string::npos) << name;
    EXPECT_EQ(load_png(e.path().string()).w, 1280) << name << " is not a 1280-wide PNG";
    numbered += name.rfind("snapshot-", 0) == 0 ? 1 : 0;
  }
  EXPECT_GE(numbered, 2u);
  EXPECT_EQ(load_png((dir / "latest.png").string()).h, 800);

  // The snapshot with data shows the map fitted (occupied dark, free light) and alpha's points.
  auto view = last_view(log.substr(0, log.find(shot + " written")));
  ASSERT_TRUE(view) << view.message() << "\n" << log;
  const Image img = load_png(shot);
  ASSERT_EQ(img.w, 1280) << shot;
  EXPECT_GT(view->scale(), 50.0) << "the 10 x 8 m map should fill most of the 860 px map area";
  EXPECT_TRUE(close_to(img.at(*view, {-1.0, 1.0}), viewer::default_robot_color("alpha")))
      << "alpha's points: got " << str(img.at(*view, {-1.0, 1.0}));
  EXPECT_LT(brightness(img.at(*view, {3.5, -1.0})), 0.25f) << str(img.at(*view, {3.5, -1.0}));
  EXPECT_GT(brightness(img.at(*view, {0.5, -1.0})), 0.8f) << str(img.at(*view, {0.5, -1.0}));
}

}  // namespace
}  // namespace slam
