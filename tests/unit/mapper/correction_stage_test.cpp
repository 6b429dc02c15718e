// CorrectionStage with a real Mapper on a temporary store (no DDS): observations wait for their
// keyframe, then reach the grid and the store with its id; with SLAM off they pass straight through;
// initial poses are checked before anything changes; a reopened store restores every correction.
#include "mapper/core/correction_stage.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "mapper/core/map_error.hpp"
#include "mapper_test_data.hpp"
#include "room_scene.hpp"
#include "temp_dir.hpp"

namespace slam::mapper {
namespace {

constexpr int64_t kStepNs = 100'000'000;  // 10 Hz
constexpr double kStepM = 0.05;           // 0.5 m/s: a keyframe (0.4 m) closes after 8 steps
constexpr double kWallY = 1.03;

class CorrectionStageTest : public ::testing::Test {
 protected:
  CorrectionStageTest() {
    options_.store = (dir_.path() / "map.db").string();
    options_.grid = test_data::small();
    options_.robot_filter.radius_m = 0.0;
  }

  std::unique_ptr<Mapper> make_mapper() {
    auto mapper = Mapper::create(options_, counters_, 1, [] {});
    EXPECT_TRUE(mapper.is_ok()) << mapper.message();
    return mapper ? std::move(*mapper) : nullptr;
  }

  // `robot` at odometry pose (x, y, theta) seeing the wall y = kWallY over x +- 0.3, at time `step`
  // (robot_stamp_ns: on the robot's own clock, 0 when it sends none).
  static void observe(CorrectionStage& stage, Mapper& mapper, const std::string& robot, int step, double x,
                      double y = 0.0, double theta = 0.0, int64_t robot_stamp_ns = 0) {
    std::vector<Vec2> hits;
    for (int i = -3; i <= 3; ++i) hits.push_back({x + 0.1 * i + 0.03, kWallY});
    const int64_t stamp = step * kStepNs;
    stage.add(mapper,
              RobotScan{robot, static_cast<uint64_t>(step), stamp,
                        ObservationView{x, y, theta, true, hits, {}}, 0, Pose{}, robot_stamp_ns},
              stamp);
  }

  // Drives `robot` along y = 0 from x = -1.5 for `steps` steps starting at time step `first`.
  static void drive(CorrectionStage& stage, Mapper& mapper, const std::string& robot, int first, int steps) {
    for (int i = 0; i < steps; ++i) observe(stage, mapper, robot, first + i, -1.5 + kStepM * (first + i));
  }

  static void step(CorrectionStage& stage, Mapper& mapper, int at_step) {
    stage.step(mapper, at_step * kStepNs, at_step * kStepNs);
  }

  // Whether any observation touched the cell holding `p`.
  static bool touched(const Mapper& mapper, Vec2 p) {
    const auto cell = mapper.grid().cell_at(p);
    return cell && mapper.grid().log_odds(cell->x, cell->y) != 0;
  }

  // Stored observations' keyframe ids per robot (the mapper must be gone: its batch is committed).
  std::map<std::string, std::vector<KeyframeId>> stored_keyframe_ids() {
    std::map<std::string, std::vector<KeyframeId>> ids;
    auto store = ObservationStore::open(options_.store);
    EXPECT_TRUE(store.is_ok()) << store.message();
    if (!store) return ids;
    EXPECT_TRUE(store->for_each(
        [&](const ObservationRecord& r) { ids[std::string(r.robot_id)].push_back(r.keyframe_id); }));
    return ids;
  }

  std::vector<Keyframe> stored_keyframes() {
    auto store = ObservationStore::open(options_.store);
    EXPECT_TRUE(store.is_ok()) << store.message();
    if (!store) return {};
    auto keyframes = store->keyframes();
    EXPECT_TRUE(keyframes.is_ok()) << keyframes.message();
    return keyframes ? *keyframes : std::vector<Keyframe>{};
  }

  static std::vector<correction::RobotCorrection> changed(CorrectionStage& stage) {
    std::vector<correction::RobotCorrection> out;
    stage.take_changed(out);
    return out;
  }

  testkit::TempDir dir_{"correction_stage"};
  MapperOptions options_;
  Counters counters_;
  correction::CorrectorOptions corrector_;
};

TEST_F(CorrectionStageTest, HoldsObservationsUntilTheirKeyframeIsFinalised) {
  auto mapper = make_mapper();
  ASSERT_TRUE(mapper);
  CorrectionStage stage(true, corrector_);
  const Vec2 first_wall{-1.5 + 0.03, kWallY};

  drive(stage, *mapper, "r1", 0, 4);  // 0.15 m: the keyframe is still open
  step(stage, *mapper, 4);
  EXPECT_FALSE(touched(*mapper, first_wall)) << "an observation reached the grid before its keyframe closed";
  EXPECT_EQ(stage.stats().keyframes, 0);
  EXPECT_EQ(stage.held_observations(), 4);  // all of them wait for their keyframe to close
  EXPECT_EQ(stage.stats().open_messages, 4);

  drive(stage, *mapper, "r1", 4, 6);  // past 0.4 m of travel: the keyframe closes
  step(stage, *mapper, 10);
  EXPECT_TRUE(touched(*mapper, first_wall)) << "the finalised keyframe's observations are not in the grid";
  EXPECT_GE(stage.stats().keyframes, 1);
  EXPECT_LT(stage.held_observations(), 10);
  EXPECT_EQ(stage.held_observations(), stage.stats().open_messages)
      << "held back past their keyframe's match";

  // A robot that goes silent: its open keyframe is finalised once it is stale.
  observe(stage, *mapper, "r2", 10, 0.0, 0.5);
  observe(stage, *mapper, "r2", 11, 0.05, 0.5);
  const Vec2 r2_wall{0.03, kWallY};
  const bool touched_by_r1 = touched(*mapper, r2_wall);
  step(stage, *mapper, 12);
  ASSERT_FALSE(touched_by_r1) << "test setup: r1 must not have seen r2's wall";
  EXPECT_FALSE(touched(*mapper, r2_wall));
  step(stage, *mapper, 12 + 60);  // 6 s later: longer than the keyframe's time span
  EXPECT_TRUE(touched(*mapper, r2_wall)) << "a silent robot's keyframe was never finalised";
  EXPECT_EQ(stage.held_observations(), 0);

  mapper->commit();
  mapper.reset();
  const auto ids = stored_keyframe_ids();
  std::set<KeyframeId> referenced;
  for (const auto& [robot, robot_ids] : ids)
    for (const KeyframeId id : robot_ids) {
      EXPECT_NE(id, 0u) << robot;
      referenced.insert(id);
    }
  ASSERT_EQ(ids.count("r1"), 1u);
  ASSERT_EQ(ids.count("r2"), 1u);
  EXPECT_GE(ids.at("r1").size(), 8u);  // the closed keyframe's observations (the rest are held)
  EXPECT_EQ(ids.at("r2").size(), 2u);
  std::set<KeyframeId> stored;
  for (const Keyframe& k : stored_keyframes()) stored.insert(k.id);
  for (const KeyframeId id : referenced)
    EXPECT_EQ(stored.count(id), 1u) << "keyframe " << id << " not stored";
}

TEST_F(CorrectionStageTest, WithSlamOffObservationsPassStraightThrough) {
  auto mapper = make_mapper();
  ASSERT_TRUE(mapper);
  CorrectionStage stage(false, corrector_);
  observe(stage, *mapper, "r1", 0, 0.0);
  EXPECT_TRUE(touched(*mapper, {0.03, kWallY}));
  step(stage, *mapper, 1);
  EXPECT_TRUE(changed(stage).empty());
  EXPECT_TRUE(stage.set_initial_pose(*mapper, "r1", Pose{0.5, 0.5, 0.0}).is(MapError::InvalidRequest));
  EXPECT_TRUE(changed(stage).empty());

  mapper->commit();
  mapper.reset();
  const auto ids = stored_keyframe_ids();
  ASSERT_EQ(ids.count("r1"), 1u);
  EXPECT_EQ(ids.at("r1"), std::vector<KeyframeId>{0});
  EXPECT_TRUE(stored_keyframes().empty());
}

TEST_F(CorrectionStageTest, RejectsBadInitialPosesAndChangesNothing) {
  auto mapper = make_mapper();
  ASSERT_TRUE(mapper);
  CorrectionStage stage(true, corrector_);
  drive(stage, *mapper, "r1", 0, 12);
  step(stage, *mapper, 12);
  (void)changed(stage);  // whatever the first keyframe set

  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto unknown = stage.set_initial_pose(*mapper, "nobody", Pose{0.5, 0.5, 0.0});
  EXPECT_FALSE(unknown);
  EXPECT_NE(unknown.message().find("unknown robot"), std::string::npos) << unknown.message();
  EXPECT_TRUE(unknown.is(MapError::UnknownRobot));
  EXPECT_TRUE(stage.set_initial_pose(*mapper, "nobody", Pose{nan, 0.5, 0.0}).is(MapError::UnknownRobot));
  EXPECT_TRUE(stage.set_initial_pose(*mapper, "r1", Pose{nan, 0.5, 0.0}).is(MapError::InvalidRequest));
  EXPECT_FALSE(stage.set_initial_pose(*mapper, "r1", Pose{0.5, 0.5, nan}));
  const auto outside = stage.set_initial_pose(*mapper, "r1", Pose{50.0, 0.5, 0.0});
  EXPECT_FALSE(outside);
  EXPECT_TRUE(outside.is(MapError::InvalidRequest));
  EXPECT_EQ(failure_result(unknown.code()), RequestResult::UnknownRobot);
  EXPECT_EQ(failure_result(outside.code()), RequestResult::InvalidRequest);
  EXPECT_NE(outside.message().find("outside the map"), std::string::npos) << outside.message();
  EXPECT_TRUE(changed(stage).empty()) << "a refused initial pose changed a correction";
}

TEST_F(CorrectionStageTest, InitialPosePlacesTheLastOdometryPose) {
  auto mapper = make_mapper();
  ASSERT_TRUE(mapper);
  CorrectionStage stage(true, corrector_);
  drive(stage, *mapper, "r1", 0, 12);  // last odometry pose (-0.95, 0, 0)
  step(stage, *mapper, 12);
  (void)changed(stage);

  const Pose target{0.7, -0.4, 0.5};
  ASSERT_TRUE(stage.set_initial_pose(*mapper, "r1", target));
  const auto out = changed(stage);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].robot, "r1");
  EXPECT_EQ(out[0].source, correction::CorrectionSource::Operator);
  const Pose placed = out[0].map_from_odom.compose(Pose{-1.5 + kStepM * 11, 0.0, 0.0});
  EXPECT_NEAR(placed.x, target.x, 1e-9);
  EXPECT_NEAR(placed.y, target.y, 1e-9);
  EXPECT_NEAR(placed.theta, target.theta, 1e-9);
}

TEST_F(CorrectionStageTest, RestoreAfterReopeningGivesEveryRobotItsCorrection) {
  std::map<std::string, Pose> before;
  {
    auto mapper = make_mapper();
    ASSERT_TRUE(mapper);
    CorrectionStage stage(true, corrector_);
    drive(stage, *mapper, "r1", 0, 12);
    drive(stage, *mapper, "r2", 0, 12);
    step(stage, *mapper, 12);
    // Non-trivial corrections: an operator moves r2, and its next keyframes carry that.
    ASSERT_TRUE(stage.set_initial_pose(*mapper, "r2", Pose{0.3, 0.6, 0.2}));
    for (int i = 12; i < 30; ++i) observe(stage, *mapper, "r2", i, -1.5 + kStepM * i);
    step(stage, *mapper, 30);
    step(stage, *mapper, 30 + 60);  // both robots' open keyframes go stale
    for (const auto& c : changed(stage)) before[c.robot] = c.map_from_odom;
    ASSERT_EQ(before.size(), 2u);
    ASSERT_GT(std::hypot(before["r2"].x, before["r2"].y), 0.1) << "test setup: r2's correction is trivial";
    mapper->commit();
  }

  auto mapper = make_mapper();
  ASSERT_TRUE(mapper);
  CorrectionStage stage(true, corrector_);
  ASSERT_TRUE(stage.restore(*mapper));
  const auto after = changed(stage);
  ASSERT_EQ(after.size(), before.size());
  for (const auto& c : after) {
    ASSERT_EQ(before.count(c.robot), 1u) << c.robot;
    EXPECT_EQ(c.source, correction::CorrectionSource::Restored) << c.robot;
    const Pose& b = before[c.robot];
    EXPECT_NEAR(c.map_from_odom.x, b.x, 1e-9) << c.robot;
    EXPECT_NEAR(c.map_from_odom.y, b.y, 1e-9) << c.robot;
    EXPECT_NEAR(c.map_from_odom.theta, b.theta, 1e-9) << c.robot;
  }
}

}  // namespace
}  // namespace slam::mapper

namespace slam::mapper {
namespace {

TEST_F(CorrectionStageTest, ARobotResetDropsItsWaitingObservationsAndItsKeyframes) {
  auto mapper = make_mapper();
  ASSERT_TRUE(mapper);
  CorrectionStage stage(true, corrector_);
  drive(stage, *mapper, "r1", 0, 12);  // one keyframe closed, the next one open
  step(stage, *mapper, 12);
  ASSERT_GE(stage.stats().keyframes, 1);
  const Vec2 open_wall{-1.5 + kStepM * 11 + 0.03 + 0.3, kWallY};  // seen only by the open keyframe
  ASSERT_FALSE(touched(*mapper, open_wall));

  EXPECT_EQ(stage.reset_robot("r1"), static_cast<size_t>(stage.stats().keyframes));
  EXPECT_EQ(stage.reset_robot("ghost"), 0u);
  step(stage, *mapper, 12 + 60);  // long after: the dropped keyframe would have gone stale
  EXPECT_FALSE(touched(*mapper, open_wall)) << "an observation held before the reset reached the grid";
  EXPECT_EQ(stage.stats().robots_reset, 1);
}

TEST_F(CorrectionStageTest, LocalisingOnlyTheLoadedMapStaysAsItWasAndTheRobotIsFoundOnIt) {
  // A room mapped earlier, loaded as the store's prior; a laser robot switched on in it with its
  // odometry at (0, 0, 0) drives a slow circle.
  const std::vector<correction::testing_scene::Wall> walls = correction::testing_scene::room();
  const correction::testing_scene::WallMap room(walls, testkit::centred_geometry({-0.5, -0.5}, {6.5, 5.5}));
  MapImage prior{static_cast<uint32_t>(room.geometry.width),
                 static_cast<uint32_t>(room.geometry.height),
                 room.geometry.resolution,
                 room.geometry.origin.x,
                 room.geometry.origin.y,
                 0.0,
                 {}};
  for (uint8_t c : room.cells) prior.cells.push_back(c == kCellOccupied ? kMapOccupied : kMapFree);
  {
    auto store = ObservationStore::open(options_.store);
    ASSERT_TRUE(store.is_ok()) << store.message();
    ASSERT_TRUE(store->save_prior(prior));
  }
  options_.grid.resolution = room.geometry.resolution;
  auto mapper = make_mapper();
  ASSERT_TRUE(mapper);
  ASSERT_TRUE(mapper->has_prior());
  ASSERT_TRUE(mapper->has_walls());
  const std::vector<uint8_t> classes_before(mapper->grid().classes().begin(), mapper->grid().classes().end());
  corrector_.localise_only = true;
  CorrectionStage stage(true, corrector_);
  ASSERT_TRUE(stage.restore(*mapper));

  Pose truth{4.6, 3.0, 2.0}, odometry;
  std::optional<correction::RobotCorrection> last;
  for (int i = 0; i < 150; ++i) {
    const Pose motion{0.02, 0.0, 0.02};
    truth = truth.compose(motion);
    odometry = odometry.compose(motion);
    const std::vector<Vec2> hits = correction::testing_scene::laser_hits(walls, truth, odometry);
    const int64_t stamp = i * kStepNs;
    stage.add(
        *mapper,
        RobotScan{"r1", static_cast<uint64_t>(i), stamp,
                  ObservationView{odometry.x, odometry.y, odometry.theta, true, hits, {}}, 0, Pose{}, 0},
        stamp);
    step(stage, *mapper, i);
    for (const auto& c : changed(stage)) last = c;
  }
  ASSERT_TRUE(last);
  EXPECT_EQ(last->placement, correction::Placement::Placed);
  EXPECT_LT(distance(last->map_from_odom.compose(odometry).position(), truth.position()), 0.05);
  EXPECT_GT(stage.localised_observations(), 100);
  const std::vector<uint8_t> classes_after(mapper->grid().classes().begin(), mapper->grid().classes().end());
  EXPECT_EQ(classes_after, classes_before) << "the loaded map changed";
  mapper->commit();
  mapper.reset();
  EXPECT_TRUE(stored_keyframe_ids().empty()) << "an observation was stored";
  EXPECT_TRUE(stored_keyframes().empty()) << "a keyframe was stored";
}

TEST_F(CorrectionStageTest, TheRobotStampWaitsWithItsObservationAndIsStoredWithIt) {
  auto mapper = make_mapper();
  ASSERT_TRUE(mapper);
  CorrectionStage stage(true, corrector_);
  const auto robot_stamp = [](int step) { return 1'000'000'000 + step * 37; };
  for (int i = 0; i < 12; ++i) observe(stage, *mapper, "r1", i, -1.5 + kStepM * i, 0.0, 0.0, robot_stamp(i));
  step(stage, *mapper, 12);
  step(stage, *mapper, 12 + 60);  // the open keyframe goes stale: every observation is stored
  EXPECT_EQ(stage.held_observations(), 0);
  mapper->commit();
  mapper.reset();
  auto store = ObservationStore::open(options_.store);
  ASSERT_TRUE(store.is_ok()) << store.message();
  int stored = 0;
  ASSERT_TRUE(store->for_each([&](const ObservationRecord& r) {
    EXPECT_EQ(r.robot_stamp_ns, robot_stamp(static_cast<int>(r.seq))) << "seq " << r.seq;
    ++stored;
  }));
  EXPECT_EQ(stored, 12);
}

}  // namespace
}  // namespace slam::mapper
