// Mapper without DDS: edit replies, rebuilds after a robot reset and a resolution change, a failed
// import, observations that arrive while a rebuild runs (their robot stamps too), and trajectory requests.
#include "mapper/core/mapper.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "mapper/core/map_files.hpp"
#include "mapper_test_data.hpp"
#include "temp_dir.hpp"

namespace slam::mapper {
namespace {

class MapperCore : public ::testing::Test {
 protected:
  MapperCore() {
    options_.store = (dir_.path() / "map.db").string();
    options_.grid = test_data::small();
    options_.robot_filter.radius_m = 0.0;
  }

  std::unique_ptr<Mapper> make() {
    auto mapper = Mapper::create(options_, counters_, 1, [] {});
    EXPECT_TRUE(mapper.is_ok()) << mapper.message();
    return mapper ? std::move(*mapper) : nullptr;
  }

  // `robot` at (0, y) seeing a wall segment at x = wall_x; robot_stamp_ns 0: the robot sent none.
  static void observe(Mapper& mapper, const std::string& robot, uint64_t seq, double y, double wall_x,
                      int64_t robot_stamp_ns = 0) {
    std::vector<Vec2> hits;
    for (int i = -3; i <= 3; ++i) hits.push_back({wall_x, y + 0.1 * i + 0.03});
    mapper.integrate(
        RobotScan{robot, seq, 0, ObservationView{0.0, y, 0.0, false, hits, {}}, 0, Pose{}, robot_stamp_ns},
        0);
  }

  static bool occupied(const Mapper& mapper, Vec2 p) {
    const auto cell = mapper.grid().cell_at(p);
    return cell && (mapper.grid().cell_class(cell->x, cell->y) & kCellStateMask) == kCellOccupied;
  }

  // The only reply due; fails the test when there is not exactly one.
  static RequestReply only_reply(Mapper& mapper) {
    std::vector<RequestReply> replies = mapper.take_replies();
    EXPECT_EQ(replies.size(), 1u);
    return replies.empty() ? RequestReply{} : replies.front();
  }

  // Every stored observation's robot stamp, in store order.
  std::vector<int64_t> stored_robot_stamps() {
    std::vector<int64_t> stamps;
    auto store = ObservationStore::open(options_.store);
    EXPECT_TRUE(store.is_ok());
    EXPECT_TRUE(store->for_each([&](const ObservationRecord& r) { stamps.push_back(r.robot_stamp_ns); }));
    return stamps;
  }

  int64_t stored_observations() {
    auto store = ObservationStore::open(options_.store);
    EXPECT_TRUE(store.is_ok());
    auto count = store->count();
    return count ? *count : -1;
  }

  testkit::TempDir dir_{"mapper"};
  MapperOptions options_;
  Counters counters_;
};

TEST_F(MapperCore, ObstructAndUnobstructReplyWhatTheyDid) {
  auto mapper = make();
  mapper->submit(EditRequest{1, EditKind::Obstruct, {0.55, 0.55}, ""});
  RequestReply r = only_reply(*mapper);
  EXPECT_EQ(r.request_id, 1u);
  EXPECT_EQ(r.result, RequestResult::Ok);
  EXPECT_NE(r.message.find("obstructed the cell"), std::string::npos) << r.message;
  EXPECT_EQ(mapper->grid().obstructions().size(), 1u);

  mapper->submit(EditRequest{2, EditKind::Obstruct, {0.56, 0.56}, ""});
  r = only_reply(*mapper);
  EXPECT_EQ(r.result, RequestResult::Ok);
  EXPECT_NE(r.message.find("already obstructed"), std::string::npos) << r.message;

  mapper->submit(EditRequest{3, EditKind::Unobstruct, {0.55, 0.55}, ""});
  r = only_reply(*mapper);
  EXPECT_EQ(r.result, RequestResult::Ok);
  EXPECT_NE(r.message.find("removed 1 obstruction(s)"), std::string::npos) << r.message;
  EXPECT_TRUE(mapper->grid().obstructions().empty());

  mapper->submit(EditRequest{4, EditKind::Unobstruct, {0.55, 0.55}, ""});
  r = only_reply(*mapper);
  EXPECT_NE(r.message.find("no manual obstruction"), std::string::npos) << r.message;

  mapper->submit(EditRequest{5, EditKind::Unobstruct, {std::nan(""), 0.0}, ""});
  EXPECT_EQ(only_reply(*mapper).result, RequestResult::InvalidRequest);
  mapper->submit(EditRequest{6, static_cast<EditKind>(17), {}, ""});
  r = only_reply(*mapper);
  EXPECT_EQ(r.result, RequestResult::InvalidRequest);
  EXPECT_NE(r.message.find("unknown edit kind 17"), std::string::npos) << r.message;
}

TEST_F(MapperCore, ResetRobotRebuildsWithoutItsObservations) {
  auto mapper = make();
  observe(*mapper, "r1", 1, 0.0, 1.03);
  observe(*mapper, "r2", 1, 0.0, -1.03);
  mapper->commit();
  ASSERT_TRUE(occupied(*mapper, {1.03, 0.03}));

  mapper->submit(EditRequest{7, EditKind::ResetRobot, {}, "r1"});
  EXPECT_TRUE(mapper->rebuilding());
  mapper->wait_for_rebuild();
  const RequestReply r = only_reply(*mapper);
  EXPECT_EQ(r.result, RequestResult::Ok) << r.message;
  EXPECT_NE(r.message.find("deleted 1 observations of robot 'r1'"), std::string::npos) << r.message;
  EXPECT_TRUE(mapper->take_swapped());
  EXPECT_FALSE(mapper->take_swapped());
  EXPECT_FALSE(occupied(*mapper, {1.03, 0.03}));
  EXPECT_TRUE(occupied(*mapper, {-1.03, 0.03}));

  mapper->submit(EditRequest{8, EditKind::ResetRobot, {}, "r1"});
  EXPECT_EQ(only_reply(*mapper).result, RequestResult::UnknownRobot);
  EXPECT_FALSE(mapper->rebuilding());
}

TEST_F(MapperCore, ResolutionChangeRebuildsAndIsKeptAcrossRestarts) {
  {
    auto mapper = make();
    observe(*mapper, "r1", 1, 0.0, 1.03);
    const GridConfig c = mapper->grid().config();
    mapper->submit(LayoutRequest{9, 0.05, c.origin_x, c.origin_y, 0.0, 0.0, -1.0, false});
    mapper->wait_for_rebuild();
    const RequestReply r = only_reply(*mapper);
    EXPECT_EQ(r.result, RequestResult::Ok) << r.message;
    EXPECT_EQ(mapper->grid().resolution(), 0.05);
    EXPECT_TRUE(occupied(*mapper, {1.03, 0.03}));
    // The version numbers a new layout: the swap must publish a snapshot with a new version.
    EXPECT_TRUE(mapper->take_swapped());
    EXPECT_EQ(mapper->prepare_snapshot(true).version, 1u);

    mapper->submit(LayoutRequest{10, 0.05, c.origin_x, c.origin_y, 0.0, 0.0, -1.0, false});
    EXPECT_NE(only_reply(*mapper).message.find("unchanged"), std::string::npos);
    mapper->submit(LayoutRequest{11, -1.0, c.origin_x, c.origin_y, 0.0, 0.0, -1.0, false});
    EXPECT_EQ(only_reply(*mapper).result, RequestResult::InvalidRequest);
  }
  auto restarted = make();
  EXPECT_EQ(restarted->grid().resolution(), 0.05);
  EXPECT_TRUE(occupied(*restarted, {1.03, 0.03}));
}

TEST_F(MapperCore, FailedImportKeepsThePreviousPrior) {
  auto mapper = make();
  observe(*mapper, "r1", 1, 0.0, 1.03);
  const std::string good = (dir_.path() / "good.yaml").string();
  ASSERT_TRUE(export_map_file(mapper->grid(), good).ok());
  mapper->submit(FileRequest{12, FileAction::Import, good});
  mapper->wait_for_rebuild();
  ASSERT_EQ(only_reply(*mapper).result, RequestResult::Ok);

  const std::string bad = (dir_.path() / "bad.yaml").string();
  std::ofstream(bad) << "image: missing.pgm\nresolution: nonsense\n";
  mapper->submit(FileRequest{13, FileAction::Import, bad});
  const RequestReply r = only_reply(*mapper);
  EXPECT_NE(r.result, RequestResult::Ok);
  EXPECT_FALSE(mapper->rebuilding());

  auto store = ObservationStore::open(options_.store);
  ASSERT_TRUE(store.is_ok());
  auto prior = store->load_prior();
  ASSERT_TRUE(prior.is_ok());
  ASSERT_TRUE(prior->has_value());
  const FileOutcome imported = read_map_file(good);
  ASSERT_TRUE(imported.ok());
  EXPECT_EQ((*prior)->cells, imported.image->cells);
}

TEST_F(MapperCore, ObservationsDuringARebuildAreKeptAndStored) {
  auto mapper = make();
  observe(*mapper, "r1", 1, 0.0, 1.03);
  const GridConfig c = mapper->grid().config();
  mapper->submit(LayoutRequest{14, 0.05, c.origin_x, c.origin_y, 0.0, 0.0, -1.0, false});
  ASSERT_TRUE(mapper->rebuilding());
  observe(*mapper, "r2", 1, 0.5, -1.03);
  // A request during the rebuild waits for it.
  mapper->submit(EditRequest{15, EditKind::Obstruct, {0.0, -1.5}, ""});
  EXPECT_TRUE(mapper->take_replies().empty());

  mapper->wait_for_rebuild();
  const std::vector<RequestReply> replies = mapper->take_replies();
  ASSERT_EQ(replies.size(), 2u);
  EXPECT_EQ(replies[0].request_id, 14u);
  EXPECT_EQ(replies[1].request_id, 15u);
  EXPECT_EQ(mapper->grid().resolution(), 0.05);
  EXPECT_TRUE(occupied(*mapper, {1.03, 0.03}));
  EXPECT_TRUE(occupied(*mapper, {-1.03, 0.53}));
  mapper->commit();
  EXPECT_EQ(stored_observations(), 2);
}

TEST_F(MapperCore, RobotStampsAreStoredAlsoWhenARebuildHeldTheObservationBack) {
  auto mapper = make();
  observe(*mapper, "r1", 1, 0.0, 1.03, 11);
  const GridConfig c = mapper->grid().config();
  mapper->submit(LayoutRequest{14, 0.05, c.origin_x, c.origin_y, 0.0, 0.0, -1.0, false});
  ASSERT_TRUE(mapper->rebuilding());
  observe(*mapper, "r2", 1, 0.5, -1.03, 22);
  observe(*mapper, "r2", 2, 0.6, -1.03);
  mapper->wait_for_rebuild();
  mapper->commit();
  EXPECT_EQ(stored_robot_stamps(), (std::vector<int64_t>{11, 22, 0}));
}

TEST_F(MapperCore, ATrajectoryRequestWritesTheRobotsPosesWithItsStamps) {
  auto mapper = make();
  observe(*mapper, "r1", 1, 0.0, 1.03, 2'000'000'000);
  observe(*mapper, "r2", 1, 0.5, -1.03, 9'000'000'000);
  observe(*mapper, "r1", 2, 0.25, 1.03, 2'500'000'000);  // not committed yet: the request still sees it
  const std::string path = (dir_.path() / "r1.tum").string();
  mapper->submit(FileRequest{20, FileAction::ExportTrajectoryTum, path, "r1"});
  const RequestReply done = only_reply(*mapper);
  EXPECT_EQ(done.result, RequestResult::Ok) << done.message;
  EXPECT_NE(done.message.find("wrote 2 poses of robot 'r1' (2.000000000 to 2.500000000 s)"),
            std::string::npos)
      << done.message;
  std::ifstream in(path);
  std::string first, second;
  std::getline(in, first);
  std::getline(in, second);
  EXPECT_EQ(first, "2.000000000 0.000000 0.000000 0 0 0 0.000000000 1.000000000");
  EXPECT_EQ(second, "2.500000000 0.000000 0.250000 0 0 0 0.000000000 1.000000000");

  mapper->submit(FileRequest{21, FileAction::ExportTrajectoryCarmen, path, "ghost"});
  EXPECT_EQ(only_reply(*mapper).result, RequestResult::UnknownRobot);
  mapper->submit(FileRequest{22, FileAction::ExportTrajectoryTum, "/nonexistent-dir/r1.tum", "r1"});
  EXPECT_EQ(only_reply(*mapper).result, RequestResult::IoError);
  mapper->submit(FileRequest{23, FileAction::ExportTrajectoryTum, "", "r1"});
  EXPECT_EQ(only_reply(*mapper).result, RequestResult::InvalidRequest);
}

TEST_F(MapperCore, ReRenderAppliesTheKeyframeCorrectionsAndARestartKeepsThem) {
  // Odometry-frame scans of a wall, keyframes 1 and 2; integrated live with no correction yet.
  std::vector<std::vector<Vec2>> scans;
  for (int i = 0; i < 6; ++i) {
    std::vector<Vec2> hits;
    for (int k = -3; k <= 3; ++k) hits.push_back({1.2, 0.1 * i + 0.1 * k});
    scans.push_back(hits);
  }
  const auto keyframe_of = [](size_t i) -> KeyframeId { return i < 3 ? 1 : 2; };
  const std::vector<Keyframe> optimised{{1, "r1", 0, Pose{}, Pose{0.1, -0.05, 0.02}},
                                        {2, "r1", 0, Pose{}, Pose{-0.15, 0.1, -0.04}}};
  auto expected = OccupancyGrid::create(test_data::small());
  ASSERT_TRUE(expected.is_ok());
  std::vector<Vec2> hits, misses;
  for (size_t i = 0; i < scans.size(); ++i) {
    const ObservationView odom{0.0, 0.1 * static_cast<double>(i), 0.0, false, scans[i], {}};
    ASSERT_TRUE(
        expected->integrate(to_map_frame(optimised[keyframe_of(i) - 1].map_from_odom, odom, hits, misses)));
  }
  {
    auto mapper = make();
    for (size_t i = 0; i < scans.size(); ++i) {
      const ObservationView odom{0.0, 0.1 * static_cast<double>(i), 0.0, false, scans[i], {}};
      mapper->integrate(RobotScan{"r1", i + 1, 0, odom, keyframe_of(i), Pose{}}, 0);
    }
    EXPECT_FALSE(test_data::same_grid(mapper->grid(), *expected));
    ASSERT_TRUE(mapper->save_keyframes(optimised).is_ok());
    mapper->rerender();
    ASSERT_TRUE(mapper->rebuilding());
    mapper->wait_for_rebuild();
    EXPECT_FALSE(mapper->rebuilding());
    EXPECT_TRUE(mapper->take_replies().empty());  // nobody asked: no reply
    // Redrawn in place (a partial re-render): the changed tiles go out in the next patch.
    EXPECT_FALSE(mapper->take_swapped());
    EXPECT_TRUE(mapper->grid().dirty_tiles().any());
    EXPECT_EQ(counters_.get("rerenders_partial").load(), 1);
    EXPECT_EQ(counters_.get("rerender_observations").load(), 6);
    EXPECT_TRUE(test_data::same_grid(mapper->grid(), *expected));
  }
  auto restarted = make();
  EXPECT_EQ(restarted->corrections().size(), 2u);
  EXPECT_TRUE(test_data::same_grid(restarted->grid(), *expected));
}

TEST_F(MapperCore, ACorrectedObservationIsIntegratedInTheMapFrameAndStoredRaw) {
  auto mapper = make();
  std::vector<Vec2> hits;
  for (int k = -3; k <= 3; ++k) hits.push_back({1.03, 0.1 * k + 0.03});
  const Pose correction{0.0, 0.0, std::acos(-1.0) / 2};  // a quarter turn: x = 1.03 lands on y = 1.03
  mapper->integrate(RobotScan{"r1", 1, 0, ObservationView{0.0, 0.0, 0.0, false, hits, {}}, 0, correction}, 0);
  EXPECT_TRUE(occupied(*mapper, {-0.03, 1.03}));
  EXPECT_FALSE(occupied(*mapper, {1.03, 0.03}));
  mapper->commit();
  auto store = ObservationStore::open(options_.store);
  ASSERT_TRUE(store.is_ok());
  std::vector<Vec2> stored;
  ASSERT_TRUE(store->for_each(
      [&](const ObservationRecord& r) { stored.assign(r.obs.hits.begin(), r.obs.hits.end()); }));
  EXPECT_EQ(stored, hits);
}

}  // namespace
}  // namespace slam::mapper
