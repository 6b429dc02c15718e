// ObservationStore's pose-correction support: keyframe ids on observations, the keyframes table
// (upsert in the append batch, load all, deleted with their robot), the rows of one keyframe (what a
// partial re-render reads) and the migration of a store written by schema 1.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <string>
#include <vector>

#include "mapper/core/observation_store.hpp"
#include "temp_dir.hpp"

namespace slam::mapper {
namespace {

// The observations table as schema 1 created it, with one row (hits: one point (1, 2)).
void write_schema_1_store(const std::filesystem::path& path) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  const char* sql = R"sql(
CREATE TABLE observations(
  id INTEGER PRIMARY KEY,
  robot TEXT NOT NULL,
  seq INTEGER NOT NULL,
  stamp_ns INTEGER NOT NULL,
  x REAL NOT NULL, y REAL NOT NULL, theta REAL NOT NULL, has_heading INTEGER NOT NULL,
  hits BLOB, misses BLOB);
CREATE TABLE obstructions(x REAL NOT NULL, y REAL NOT NULL, PRIMARY KEY(x, y));
CREATE TABLE config(key TEXT PRIMARY KEY, value REAL NOT NULL);
CREATE TABLE prior(
  id INTEGER PRIMARY KEY CHECK(id = 1),
  width INTEGER NOT NULL, height INTEGER NOT NULL, resolution REAL NOT NULL,
  origin_x REAL NOT NULL, origin_y REAL NOT NULL, origin_yaw REAL NOT NULL, cells BLOB NOT NULL);
INSERT INTO observations(robot, seq, stamp_ns, x, y, theta, has_heading, hits, misses)
  VALUES('old', 7, 70, 0.5, 0.25, 0.0, 0,
         X'000000000000F03F0000000000000040', X'');
PRAGMA user_version=1;
)sql";
  char* error = nullptr;
  EXPECT_EQ(sqlite3_exec(db, sql, nullptr, nullptr, &error), SQLITE_OK) << (error ? error : "");
  sqlite3_free(error);
  sqlite3_close(db);
}

std::vector<KeyframeId> keyframe_ids_of_observations(ObservationStore& store) {
  std::vector<KeyframeId> ids;
  EXPECT_TRUE(store.for_each([&](const ObservationRecord& r) { ids.push_back(r.keyframe_id); }).is_ok());
  return ids;
}

Keyframe keyframe(KeyframeId id, const std::string& robot, double dx) {
  return Keyframe{id, robot, 1, Pose{static_cast<double>(id), 2.0, 0.1}, Pose{dx, -dx, 0.01 * dx}};
}

TEST(StoreKeyframes, ASchema1StoreOpensWithKeyframeZeroAndTakesKeyframes) {
  testkit::TempDir dir("mapper");
  const auto path = dir.path() / "old.db";
  write_schema_1_store(path);
  {
    auto store = ObservationStore::open(path);
    ASSERT_TRUE(store.is_ok()) << store.message();
    std::vector<Vec2> hits;
    ASSERT_TRUE(store
                    ->for_each([&](const ObservationRecord& r) {
                      EXPECT_EQ(r.robot_id, "old");
                      EXPECT_EQ(r.seq, 7u);
                      EXPECT_EQ(r.keyframe_id, 0u);
                      EXPECT_EQ(r.robot_stamp_ns, 0);
                      hits.assign(r.obs.hits.begin(), r.obs.hits.end());
                    })
                    .is_ok());
    EXPECT_EQ(hits, (std::vector<Vec2>{{1.0, 2.0}}));
    const Keyframe k = keyframe(3, "new", 0.5);
    ASSERT_TRUE(store->save_keyframes({&k, 1}).is_ok());
    ASSERT_TRUE(store->append("new", 1, 80, 3, ObservationView{}).is_ok());
  }
  auto reopened = ObservationStore::open(path);  // now at the current schema: no second migration
  ASSERT_TRUE(reopened.is_ok()) << reopened.message();
  std::vector<int64_t> rows;
  ASSERT_TRUE(reopened->rows_of(3, 0, 100, [&](int64_t row) { rows.push_back(row); }));
  EXPECT_EQ(rows, (std::vector<int64_t>{2}));
  EXPECT_EQ(keyframe_ids_of_observations(*reopened), (std::vector<KeyframeId>{0, 3}));
  auto keyframes = reopened->keyframes();
  ASSERT_TRUE(keyframes.is_ok());
  EXPECT_EQ(*keyframes, (std::vector<Keyframe>{keyframe(3, "new", 0.5)}));
}

TEST(StoreKeyframes, UpsertReplacesByIdAndLoadsInIdOrder) {
  testkit::TempDir dir("mapper");
  auto store = ObservationStore::open(dir.path() / "m.db");
  ASSERT_TRUE(store.is_ok());
  const std::vector<Keyframe> first{keyframe(5, "a", 0.1), keyframe(2, "b", 0.2)};
  ASSERT_TRUE(store->save_keyframes(first).is_ok());
  const std::vector<Keyframe> optimised{keyframe(5, "a", 0.3)};
  ASSERT_TRUE(store->save_keyframes(optimised).is_ok());
  auto loaded = store->keyframes();
  ASSERT_TRUE(loaded.is_ok());
  EXPECT_EQ(*loaded, (std::vector<Keyframe>{keyframe(2, "b", 0.2), keyframe(5, "a", 0.3)}));
}

TEST(StoreKeyframes, KeyframesCommitWithTheAppendBatch) {
  testkit::TempDir dir("mapper");
  const auto path = dir.path() / "m.db";
  auto writer = ObservationStore::open(path, StoreOptions{100});
  ASSERT_TRUE(writer.is_ok());
  auto reader = ObservationStore::open(path);
  ASSERT_TRUE(reader.is_ok());
  const Keyframe k = keyframe(1, "r", 0.2);
  ASSERT_TRUE(writer->save_keyframes({&k, 1}).is_ok());
  ASSERT_TRUE(writer->append("r", 1, 0, 1, ObservationView{}).is_ok());
  // Open batch: another connection (what a kill -9 would leave) sees neither.
  EXPECT_TRUE(reader->keyframes()->empty());
  EXPECT_EQ(*reader->count(), 0);
  ASSERT_TRUE(writer->flush().is_ok());
  EXPECT_EQ(reader->keyframes()->size(), 1u);
  EXPECT_EQ(keyframe_ids_of_observations(*reader), (std::vector<KeyframeId>{1}));
}

TEST(StoreKeyframes, ResettingARobotDeletesItsKeyframes) {
  testkit::TempDir dir("mapper");
  auto store = ObservationStore::open(dir.path() / "m.db");
  ASSERT_TRUE(store.is_ok());
  const std::vector<Keyframe> keyframes{keyframe(1, "a", 0.1), keyframe(2, "b", 0.2)};
  ASSERT_TRUE(store->save_keyframes(keyframes).is_ok());
  ASSERT_TRUE(store->append("a", 1, 0, 1, ObservationView{}).is_ok());
  auto deleted = store->delete_robot("a");
  ASSERT_TRUE(deleted.is_ok());
  EXPECT_EQ(*deleted, 1);
  EXPECT_EQ(*store->keyframes(), (std::vector<Keyframe>{keyframe(2, "b", 0.2)}));
}

TEST(StoreKeyframes, TheRowsOfAKeyframeComeByIndexAndReadBackInOrder) {
  testkit::TempDir dir("mapper");
  const auto path = dir.path() / "m.db";
  auto store = ObservationStore::open(path);
  ASSERT_TRUE(store.is_ok());
  std::vector<int64_t> appended;
  for (uint64_t i = 0; i < 9; ++i) {
    ASSERT_TRUE(
        store->append("r", i, 0, 1 + i % 3, ObservationView{static_cast<double>(i), 0, 0, false, {}, {}}));
    appended.push_back(store->last_row());
  }
  EXPECT_EQ(appended, (std::vector<int64_t>{1, 2, 3, 4, 5, 6, 7, 8, 9}));
  std::vector<int64_t> rows;
  ASSERT_TRUE(store->rows_of(2, 0, 100, [&](int64_t row) { rows.push_back(row); }));
  EXPECT_EQ(rows, (std::vector<int64_t>{2, 5, 8}));
  rows.clear();
  ASSERT_TRUE(store->rows_of(2, 3, 7, [&](int64_t row) { rows.push_back(row); }));
  EXPECT_EQ(rows, (std::vector<int64_t>{5}));
  std::vector<double> xs;
  const std::vector<int64_t> wanted{2, 5, 42, 8};  // 42 does not exist
  ASSERT_TRUE(store->for_each_row(wanted, [&](const ObservationRecord& r) { xs.push_back(r.obs.x); }));
  EXPECT_EQ(xs, (std::vector<double>{1, 4, 7}));
  ASSERT_TRUE(store->flush());
  sqlite3* db = nullptr;  // the plan SQLite picks: the keyframe index, not a scan of the table
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  sqlite3_stmt* st = nullptr;
  ASSERT_EQ(
      sqlite3_prepare_v2(db,
                         "EXPLAIN QUERY PLAN SELECT id FROM observations WHERE keyframe = 2 AND id BETWEEN "
                         "0 AND 100 ORDER BY id",
                         -1, &st, nullptr),
      SQLITE_OK);
  std::string plan;
  while (sqlite3_step(st) == SQLITE_ROW) plan += reinterpret_cast<const char*>(sqlite3_column_text(st, 3));
  sqlite3_finalize(st);
  sqlite3_close(db);
  EXPECT_NE(plan.find("observations_keyframe"), std::string::npos) << plan;
}

}  // namespace
}  // namespace slam::mapper
