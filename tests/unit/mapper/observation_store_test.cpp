// ObservationStore: round trip in insertion order, batching, delete by robot, persistence of
// obstructions, config and prior, and open errors for unwritable and corrupt files.
#include "mapper/core/observation_store.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "temp_dir.hpp"

namespace slam::mapper {
namespace {

struct Row {
  std::string robot;
  uint64_t seq;
  int64_t stamp;
  double x, y, theta;
  bool heading;
  std::vector<Vec2> hits, misses;
  bool operator==(const Row&) const = default;
};

std::vector<Row> read_all(ObservationStore& s) {
  std::vector<Row> rows;
  const Status st = s.for_each([&](const ObservationRecord& r) {
    rows.push_back({std::string(r.robot_id),
                    r.seq,
                    r.stamp_ns,
                    r.obs.x,
                    r.obs.y,
                    r.obs.theta,
                    r.obs.has_heading,
                    {r.obs.hits.begin(), r.obs.hits.end()},
                    {r.obs.misses.begin(), r.obs.misses.end()}});
  });
  EXPECT_TRUE(st.is_ok()) << st.message();
  return rows;
}

Status put(ObservationStore& s, const Row& r) {
  ObservationView v{r.x, r.y, r.theta, r.heading, r.hits, r.misses};
  return s.append(r.robot, r.seq, r.stamp, 0, v);
}

TEST(ObservationStore, RoundTripInInsertionOrderAcrossReopen) {
  testkit::TempDir dir("mapper");
  const auto path = dir.path() / "map.db";
  std::vector<Row> rows;
  for (int i = 0; i < 25; ++i)
    rows.push_back({i % 2 ? "alpha" : "beta",
                    static_cast<uint64_t>(i + 1),
                    1000 + i,
                    0.1 * i,
                    -0.2 * i,
                    0.3,
                    i % 3 == 0,
                    {{1.0 + i, 2.0}, {3.0, 4.0 + 1e-9 * i}},
                    i % 4 ? std::vector<Vec2>{} : std::vector<Vec2>{{5, 6}}});
  {
    auto s = ObservationStore::open(path, StoreOptions{7});
    ASSERT_TRUE(s.is_ok()) << s.message();
    for (const Row& r : rows) ASSERT_TRUE(put(*s, r).is_ok());
    EXPECT_EQ(read_all(*s), rows);  // pending batch visible before flush
    auto n = s->count();
    ASSERT_TRUE(n.is_ok());
    EXPECT_EQ(*n, 25);
  }  // destructor commits the open batch
  auto s = ObservationStore::open(path);
  ASSERT_TRUE(s.is_ok()) << s.message();
  EXPECT_EQ(read_all(*s), rows);
}

TEST(ObservationStore, OpensWhileAnotherConnectionHoldsAnOpenBatch) {
  // The re-render worker opens the store while the map loop's connection has a batch open (and
  // does not commit while the worker runs). Opening a store of the current schema must not need
  // the write lock: it used to, and the re-render then failed after 2 s with "database is locked".
  testkit::TempDir dir("mapper");
  const auto path = dir.path() / "map.db";
  auto writer = ObservationStore::open(path);
  ASSERT_TRUE(writer.is_ok()) << writer.message();
  ASSERT_TRUE(put(*writer, {"r1", 1, 0, 0, 0, 0, false, {{1, 1}}, {}}).is_ok());
  ASSERT_TRUE(writer->flush().is_ok());
  ASSERT_TRUE(put(*writer, {"r1", 2, 0, 0, 0, 0, false, {{1, 1}}, {}}).is_ok());  // batch open
  auto reader = ObservationStore::open(path);
  ASSERT_TRUE(reader.is_ok()) << reader.message();
  EXPECT_EQ(read_all(*reader).size(), 1U);  // what was committed
}

TEST(ObservationStore, DeleteByRobot) {
  testkit::TempDir dir("mapper");
  auto s = ObservationStore::open(dir.path() / "map.db");
  ASSERT_TRUE(s.is_ok());
  for (int i = 0; i < 10; ++i)
    ASSERT_TRUE(put(*s, {i < 4 ? "r1" : "r2", 1, 0, 0, 0, 0, false, {{1, 1}}, {}}).is_ok());
  auto gone = s->delete_robot("r1");
  ASSERT_TRUE(gone.is_ok()) << gone.message();
  EXPECT_EQ(*gone, 4);
  for (const Row& r : read_all(*s)) EXPECT_EQ(r.robot, "r2");
  EXPECT_EQ(*s->delete_robot("nobody"), 0);
}

TEST(ObservationStore, ObstructionsConfigAndPriorPersist) {
  testkit::TempDir dir("mapper");
  const auto path = dir.path() / "map.db";
  GridConfig cfg;
  cfg.resolution = 0.1;
  cfg.inflation_radius = 0.35;
  cfg.legacy_mode = true;
  cfg.log_odds.hit = 77;
  MapImage prior;
  prior.width = 3;
  prior.height = 2;
  prior.resolution = 0.25;
  prior.origin_x = -1.5;
  prior.origin_yaw = 0.5;
  prior.cells = {0, 1, 2, 2, 1, 0};
  {
    auto s = ObservationStore::open(path);
    ASSERT_TRUE(s.is_ok());
    auto none = s->load_config();
    ASSERT_TRUE(none.is_ok());
    EXPECT_FALSE(none->has_value());
    ASSERT_TRUE(s->add_obstruction({1.25, 2.5}).is_ok());
    ASSERT_TRUE(s->add_obstruction({-3.0, 4.0}).is_ok());
    ASSERT_TRUE(s->add_obstruction({7.0, 7.0}).is_ok());
    ASSERT_TRUE(s->remove_obstruction({7.0, 7.0}).is_ok());
    ASSERT_TRUE(s->save_config(cfg).is_ok());
    ASSERT_TRUE(s->save_prior(prior).is_ok());
  }
  auto s = ObservationStore::open(path);
  ASSERT_TRUE(s.is_ok());
  auto obs = s->obstructions();
  ASSERT_TRUE(obs.is_ok());
  EXPECT_EQ(*obs, (std::vector<Vec2>{{1.25, 2.5}, {-3.0, 4.0}}));
  auto loaded = s->load_config();
  ASSERT_TRUE(loaded.is_ok()) << loaded.message();
  ASSERT_TRUE(loaded->has_value());
  EXPECT_DOUBLE_EQ((*loaded)->resolution, 0.1);
  EXPECT_DOUBLE_EQ((*loaded)->inflation_radius, 0.35);
  EXPECT_TRUE((*loaded)->legacy_mode);
  EXPECT_EQ((*loaded)->log_odds.hit, 77);
  auto p = s->load_prior();
  ASSERT_TRUE(p.is_ok()) << p.message();
  ASSERT_TRUE(p->has_value());
  EXPECT_EQ((*p)->cells, prior.cells);
  EXPECT_EQ((*p)->width, 3u);
  EXPECT_DOUBLE_EQ((*p)->origin_yaw, 0.5);
  ASSERT_TRUE(s->clear_obstructions().is_ok());
  EXPECT_TRUE(s->obstructions()->empty());
  ASSERT_TRUE(s->clear_prior().is_ok());
  EXPECT_FALSE(s->load_prior()->has_value());
}

TEST(ObservationStore, UnwritablePathIsAnError) {
  testkit::TempDir dir("mapper");
  auto s = ObservationStore::open(dir.path() / "no" / "such" / "dir" / "map.db");
  ASSERT_FALSE(s.is_ok());
  EXPECT_NE(s.message().find("map.db"), std::string::npos) << s.message();
}

TEST(ObservationStore, CorruptFileIsAnError) {
  testkit::TempDir dir("mapper");
  const auto path = dir.path() / "garbage.db";
  {
    std::ofstream out(path, std::ios::binary);
    for (int i = 0; i < 4096; ++i) out.put(static_cast<char>(i * 7));
  }
  auto s = ObservationStore::open(path);
  ASSERT_FALSE(s.is_ok());
  EXPECT_NE(s.message().find("garbage.db"), std::string::npos) << s.message();
  EXPECT_NE(s.message().find("not a database"), std::string::npos) << s.message();
}

}  // namespace
}  // namespace slam::mapper
