// Pose correction in the grid: the odometry -> map transform of an observation, the correction
// lookup, and rebuilds that re-render the store with keyframe corrections.
#include "mapper/core/corrections.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "mapper/core/rebuild.hpp"
#include "mapper_test_data.hpp"
#include "temp_dir.hpp"

namespace slam::mapper {
namespace {

// Three robots' observations, odometry frame, each tagged with one of keyframes 1..4 or none (0).
struct Stored {
  KeyframeId keyframe;
  double x, y;
  std::vector<Vec2> hits, misses;
  ObservationView view() const { return {x, y, 0.0, false, hits, misses}; }
};
std::vector<Stored> observations() {
  std::vector<Stored> out;
  for (int step = 0; step < 30; ++step) {
    Stored s{static_cast<KeyframeId>(step % 5), -0.5 + 0.04 * step, 0.1 * (step % 3), {}, {}};
    for (int k = 0; k < 8; ++k) s.hits.push_back({1.5, s.y - 0.4 + 0.1 * k});
    s.misses.push_back({s.x, -1.5});
    out.push_back(std::move(s));
  }
  return out;
}

KeyframeCorrections some_corrections() {
  KeyframeCorrections c;
  c.set(1, {0.12, -0.05, 0.03});
  c.set(2, {-0.2, 0.1, -0.05});
  c.set(3, {0.0, 0.0, 0.2});
  // keyframe 4 unknown: identity
  return c;
}

TEST(Corrections, ToMapFrameMovesPoseAndPointsRigidly) {
  const Pose c{1.0, 2.0, 0.5};
  const std::vector<Vec2> hits{{1.0, 0.0}, {0.0, 1.0}};
  const std::vector<Vec2> misses{{-1.0, -1.0}};
  std::vector<Vec2> h, m;
  const ObservationView map = to_map_frame(c, ObservationView{0.5, 0.5, 0.3, true, hits, misses}, h, m);
  const Pose sensor = c.compose({0.5, 0.5, 0.3});
  EXPECT_DOUBLE_EQ(map.x, sensor.x);
  EXPECT_DOUBLE_EQ(map.y, sensor.y);
  EXPECT_DOUBLE_EQ(map.theta, sensor.theta);
  ASSERT_EQ(map.hits.size(), 2u);
  ASSERT_EQ(map.misses.size(), 1u);
  for (size_t i = 0; i < hits.size(); ++i) {
    EXPECT_NEAR(map.hits[i].x, c.transform(hits[i]).x, 1e-12);
    EXPECT_NEAR(map.hits[i].y, c.transform(hits[i]).y, 1e-12);
  }
  // Distances are kept (rigid).
  EXPECT_NEAR(distance(map.hits[0], {map.x, map.y}), distance(hits[0], {0.5, 0.5}), 1e-12);
  // Without a heading theta stays 0.
  EXPECT_EQ(to_map_frame(c, ObservationView{0.5, 0.5, 0.0, false, hits, misses}, h, m).theta, 0.0);
}

TEST(Corrections, LookupIsIdentityForNoneAndUnknownKeyframes) {
  const KeyframeCorrections c = some_corrections();
  EXPECT_TRUE(is_identity(c.lookup(0)));
  EXPECT_TRUE(is_identity(c.lookup(4)));
  EXPECT_EQ(c.lookup(2), (Pose{-0.2, 0.1, -0.05}));
  KeyframeCorrections none;
  none.set(0, {1.0, 1.0, 1.0});  // 0 means "no keyframe": never corrected
  EXPECT_TRUE(none.empty());
}

class RenderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto store = ObservationStore::open(dir_.path() / "m.db");
    ASSERT_TRUE(store.is_ok());
    store_.emplace(std::move(*store));
    for (const Stored& s : observations())
      ASSERT_TRUE(store_->append("r", 1, 0, s.keyframe, s.view()).is_ok());
    ASSERT_TRUE(store_->flush().is_ok());
  }
  testkit::TempDir dir_{"mapper"};
  std::optional<ObservationStore> store_;
};

TEST_F(RenderTest, ReRenderWithCorrectionsEqualsIntegratingTheTransformedObservations) {
  const KeyframeCorrections corrections = some_corrections();
  auto direct = OccupancyGrid::create(test_data::small());
  ASSERT_TRUE(direct.is_ok());
  std::vector<Vec2> hits, misses;
  for (const Stored& s : observations())
    ASSERT_TRUE(
        direct->integrate(to_map_frame(corrections.lookup(s.keyframe), s.view(), hits, misses)).is_ok());

  RebuildStats stats;
  auto rendered = rebuild_grid(test_data::small(), *store_, &stats, corrections);
  ASSERT_TRUE(rendered.is_ok()) << rendered.message();
  EXPECT_EQ(stats.observations, 30);
  EXPECT_TRUE(test_data::same_grid(*rendered, *direct));

  auto uncorrected = rebuild_grid(test_data::small(), *store_);
  ASSERT_TRUE(uncorrected.is_ok());
  EXPECT_FALSE(test_data::same_grid(*rendered, *uncorrected));  // the corrections did move something
}

TEST_F(RenderTest, IdentityCorrectionsGiveTheUncorrectedRebuild) {
  KeyframeCorrections identity;
  for (KeyframeId id = 1; id <= 4; ++id) identity.set(id, Pose{});
  auto plain = rebuild_grid(test_data::small(), *store_);
  auto with_identity = rebuild_grid(test_data::small(), *store_, nullptr, identity);
  auto with_unknown_ids = rebuild_grid(test_data::small(), *store_, nullptr, [] {
    KeyframeCorrections c;
    c.set(99, {1.0, 0.0, 0.0});
    return c;
  }());
  ASSERT_TRUE(plain.is_ok() && with_identity.is_ok() && with_unknown_ids.is_ok());
  auto live = OccupancyGrid::create(test_data::small());
  ASSERT_TRUE(live.is_ok());
  for (const Stored& s : observations()) ASSERT_TRUE(live->integrate(s.view()).is_ok());
  EXPECT_TRUE(test_data::same_grid(*plain, *live));
  EXPECT_TRUE(test_data::same_grid(*with_identity, *live));
  EXPECT_TRUE(test_data::same_grid(*with_unknown_ids, *live));
}

}  // namespace
}  // namespace slam::mapper
