// ObservationStore's robot stamps: stored and read back with each observation, one robot's poses
// read without their points, and a store written by schema 2 migrated with 0 for its rows.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <string>
#include <utility>
#include <vector>

#include "mapper/core/observation_store.hpp"
#include "temp_dir.hpp"

namespace slam::mapper {
namespace {

// The tables as schema 2 created them, with one observation (hits: one point (1, 2)) of keyframe 4.
void write_schema_2_store(const std::filesystem::path& path) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  const char* sql = R"sql(
CREATE TABLE observations(
  id INTEGER PRIMARY KEY,
  robot TEXT NOT NULL,
  seq INTEGER NOT NULL,
  stamp_ns INTEGER NOT NULL,
  x REAL NOT NULL, y REAL NOT NULL, theta REAL NOT NULL, has_heading INTEGER NOT NULL,
  hits BLOB, misses BLOB, keyframe INTEGER NOT NULL DEFAULT 0);
CREATE TABLE keyframes(
  id INTEGER PRIMARY KEY,
  robot TEXT NOT NULL,
  segment INTEGER NOT NULL,
  odom_x REAL NOT NULL, odom_y REAL NOT NULL, odom_theta REAL NOT NULL,
  correction_x REAL NOT NULL, correction_y REAL NOT NULL, correction_theta REAL NOT NULL);
CREATE TABLE obstructions(x REAL NOT NULL, y REAL NOT NULL, PRIMARY KEY(x, y));
CREATE TABLE config(key TEXT PRIMARY KEY, value REAL NOT NULL);
CREATE TABLE prior(
  id INTEGER PRIMARY KEY CHECK(id = 1),
  width INTEGER NOT NULL, height INTEGER NOT NULL, resolution REAL NOT NULL,
  origin_x REAL NOT NULL, origin_y REAL NOT NULL, origin_yaw REAL NOT NULL, cells BLOB NOT NULL);
INSERT INTO observations(robot, seq, stamp_ns, x, y, theta, has_heading, hits, misses, keyframe)
  VALUES('old', 7, 70, 0.5, 0.25, 0.0, 0, X'000000000000F03F0000000000000040', X'', 4);
PRAGMA user_version=2;
)sql";
  char* error = nullptr;
  EXPECT_EQ(sqlite3_exec(db, sql, nullptr, nullptr, &error), SQLITE_OK) << (error ? error : "");
  sqlite3_free(error);
  sqlite3_close(db);
}

// (robot, robot stamp) of every stored observation, in store order.
std::vector<std::pair<std::string, int64_t>> robot_stamps(ObservationStore& store) {
  std::vector<std::pair<std::string, int64_t>> out;
  EXPECT_TRUE(store.for_each(
      [&](const ObservationRecord& r) { out.emplace_back(std::string(r.robot_id), r.robot_stamp_ns); }));
  return out;
}

TEST(StoreRobotStamps, StoredWithEachObservationAndReadBack) {
  testkit::TempDir dir("mapper");
  const auto path = dir.path() / "m.db";
  const std::vector<Vec2> hits{{1.0, 2.0}};
  {
    auto store = ObservationStore::open(path);
    ASSERT_TRUE(store.is_ok()) << store.message();
    ASSERT_TRUE(
        store->append("a", 1, 100, 0, ObservationView{0.0, 0.0, 0.0, false, hits, {}}, 12'500'000'000));
    ASSERT_TRUE(store->append("b", 1, 110, 0, ObservationView{}));  // the robot sent no stamp
    ASSERT_TRUE(
        store->append("a", 2, 120, 3, ObservationView{0.5, 0.25, 0.1, true, hits, {}}, 13'000'000'000));
  }
  auto store = ObservationStore::open(path);
  ASSERT_TRUE(store.is_ok()) << store.message();
  EXPECT_EQ(robot_stamps(*store), (std::vector<std::pair<std::string, int64_t>>{
                                      {"a", 12'500'000'000}, {"b", 0}, {"a", 13'000'000'000}}));
}

TEST(StoreRobotStamps, ForEachPoseReadsOneRobotInStoreOrderWithoutPoints) {
  testkit::TempDir dir("mapper");
  auto store = ObservationStore::open(dir.path() / "m.db");
  ASSERT_TRUE(store.is_ok()) << store.message();
  const std::vector<Vec2> hits{{1.0, 2.0}, {3.0, 4.0}};
  ASSERT_TRUE(store->append("a", 1, 100, 0, ObservationView{0.1, 0.2, 0.0, false, hits, {}}, 5));
  ASSERT_TRUE(store->append("ab", 1, 105, 0, ObservationView{9.0, 9.0, 0.0, false, hits, {}}, 6));
  ASSERT_TRUE(store->append("a", 2, 110, 7, ObservationView{0.3, 0.4, 0.5, true, hits, hits}, 8));
  // Pending appends included, as for_each has them.
  std::vector<ObservationRecord> seen;
  std::vector<std::string> robots;
  ASSERT_TRUE(store->for_each_pose("a", [&](const ObservationRecord& r) {
    seen.push_back(r);
    robots.emplace_back(r.robot_id);
  }));
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_EQ(robots, (std::vector<std::string>{"a", "a"}));
  EXPECT_EQ(seen[0].seq, 1u);
  EXPECT_EQ(seen[0].stamp_ns, 100);
  EXPECT_EQ(seen[0].robot_stamp_ns, 5);
  EXPECT_DOUBLE_EQ(seen[0].obs.x, 0.1);
  EXPECT_FALSE(seen[0].obs.has_heading);
  EXPECT_EQ(seen[1].keyframe_id, 7u);
  EXPECT_EQ(seen[1].robot_stamp_ns, 8);
  EXPECT_DOUBLE_EQ(seen[1].obs.theta, 0.5);
  EXPECT_TRUE(seen[1].obs.has_heading);
  for (const ObservationRecord& r : seen) {
    EXPECT_TRUE(r.obs.hits.empty());
    EXPECT_TRUE(r.obs.misses.empty());
  }
  bool any = false;
  ASSERT_TRUE(store->for_each_pose("nobody", [&](const ObservationRecord&) { any = true; }));
  EXPECT_FALSE(any);
}

TEST(StoreRobotStamps, ASchema2StoreOpensWithStampZeroAndTakesStamps) {
  testkit::TempDir dir("mapper");
  const auto path = dir.path() / "old.db";
  write_schema_2_store(path);
  {
    auto store = ObservationStore::open(path);
    ASSERT_TRUE(store.is_ok()) << store.message();
    std::vector<Vec2> hits;
    KeyframeId keyframe = 0;
    ASSERT_TRUE(store->for_each([&](const ObservationRecord& r) {
      keyframe = r.keyframe_id;
      hits.assign(r.obs.hits.begin(), r.obs.hits.end());
    }));
    EXPECT_EQ(keyframe, 4u);
    EXPECT_EQ(hits, (std::vector<Vec2>{{1.0, 2.0}}));
    ASSERT_TRUE(store->append("new", 1, 80, 0, ObservationView{}, 42));
  }
  auto reopened = ObservationStore::open(path);  // now at schema 3: no second migration
  ASSERT_TRUE(reopened.is_ok()) << reopened.message();
  EXPECT_EQ(robot_stamps(*reopened), (std::vector<std::pair<std::string, int64_t>>{{"old", 0}, {"new", 42}}));
}

}  // namespace
}  // namespace slam::mapper
