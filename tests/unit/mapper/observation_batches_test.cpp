// The rebuild's reader → integrator hand-off: observations arrive whole and in order across
// threads, and only the batches made at the start are ever used.
#include "mapper/core/observation_batches.hpp"

#include <gtest/gtest.h>

#include <set>
#include <thread>
#include <vector>

namespace slam::mapper {
namespace {

TEST(ObservationBatch, KeepsEachObservationsHitsAndMissesApart) {
  ObservationBatch b;
  const std::vector<Vec2> hits1{{1, 1}, {2, 2}}, misses1{{3, 3}};
  const std::vector<Vec2> hits2{}, misses2{{4, 4}, {5, 5}};
  b.add(7, ObservationView{0.5, 0.25, 1.0, true, hits1, misses1});
  b.add(8, ObservationView{-1.0, 2.0, 0.0, false, hits2, misses2});
  std::vector<int64_t> ids;
  b.for_each([&](int64_t id, const ObservationView& v) {
    ids.push_back(id);
    if (id == 7) {
      EXPECT_DOUBLE_EQ(v.x, 0.5);
      EXPECT_TRUE(v.has_heading);
      ASSERT_EQ(v.hits.size(), 2u);
      EXPECT_DOUBLE_EQ(v.hits[1].x, 2.0);
      ASSERT_EQ(v.misses.size(), 1u);
      EXPECT_DOUBLE_EQ(v.misses[0].y, 3.0);
    } else {
      EXPECT_DOUBLE_EQ(v.y, 2.0);
      EXPECT_TRUE(v.hits.empty());
      ASSERT_EQ(v.misses.size(), 2u);
      EXPECT_DOUBLE_EQ(v.misses[1].x, 5.0);
    }
  });
  EXPECT_EQ(ids, (std::vector<int64_t>{7, 8}));
  b.clear();
  EXPECT_TRUE(b.entries.empty() && b.points.empty());
}

TEST(ObservationBatches, DeliversEveryObservationInOrderWithTheBatchesItStartedWith) {
  constexpr int64_t kCount = 10'000;
  constexpr size_t kPerBatch = 64;
  ObservationBatches batches(3);
  std::thread producer([&] {
    ObservationBatch* b = batches.take_empty();
    for (int64_t id = 0; id < kCount; ++id) {
      const std::vector<Vec2> hits(static_cast<size_t>(id % 5), Vec2{static_cast<double>(id), 0.0});
      b->add(id, ObservationView{static_cast<double>(id), 0.0, 0.0, false, hits, {}});
      if (b->entries.size() == kPerBatch) {
        batches.push_full(b);
        b = batches.take_empty();
      }
    }
    if (!b->entries.empty()) batches.push_full(b);
    batches.finish();
  });
  int64_t next = 0;
  std::set<const ObservationBatch*> seen;
  while (ObservationBatch* b = batches.pop_full()) {
    seen.insert(b);
    b->for_each([&](int64_t id, const ObservationView& v) {
      EXPECT_EQ(id, next++);
      EXPECT_DOUBLE_EQ(v.x, static_cast<double>(id));
      ASSERT_EQ(v.hits.size(), static_cast<size_t>(id % 5));
      for (const Vec2& p : v.hits) EXPECT_DOUBLE_EQ(p.x, static_cast<double>(id));
    });
    batches.give_back(b);
  }
  producer.join();
  EXPECT_EQ(next, kCount);
  EXPECT_LE(seen.size(), 3u);  // bounded memory: the same three batches, reused
}

}  // namespace
}  // namespace slam::mapper
