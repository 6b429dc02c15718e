// When the gateway's batch of observations must be written: full by count, full by points, or due.
#include "gateway/core/batch_policy.hpp"

#include <gtest/gtest.h>

namespace slam::gateway {
namespace {

constexpr std::int64_t kMs = 1'000'000;

TEST(BatchPolicy, FullAfterTheLastObservationThatFits) {
  BatchPolicy policy({.max_observations = 3, .max_points = 1000, .max_wait_ns = 10 * kMs});
  EXPECT_TRUE(policy.empty());
  EXPECT_FALSE(policy.add(5, 0));
  EXPECT_FALSE(policy.add(5, 1));
  EXPECT_TRUE(policy.add(5, 2));
  policy.written();
  EXPECT_TRUE(policy.empty());
  EXPECT_FALSE(policy.add(5, 3)) << "a written batch starts over";
}

TEST(BatchPolicy, AnObservationThatWouldOutgrowTheDatagramStartsTheNextBatch) {
  BatchPolicy policy({.max_observations = 100, .max_points = 40, .max_wait_ns = 10 * kMs});
  EXPECT_TRUE(policy.fits(16));
  EXPECT_FALSE(policy.add(16, 0));
  EXPECT_FALSE(policy.add(16, 0));
  EXPECT_FALSE(policy.fits(16)) << "48 points would go over 40: the batch is written first";
  EXPECT_TRUE(policy.fits(8)) << "exactly at the limit still fits";
  EXPECT_TRUE(policy.add(8, 0)) << "and fills the batch";
  policy.written();
  EXPECT_TRUE(policy.fits(500)) << "a message larger than the limit goes alone into an empty batch";
  EXPECT_TRUE(policy.add(500, 0));
}

TEST(BatchPolicy, DueWhenTheOldestObservationHasWaitedTheLimit) {
  BatchPolicy policy({.max_observations = 100, .max_points = 1000, .max_wait_ns = 10 * kMs});
  EXPECT_FALSE(policy.due(1000 * kMs)) << "an empty batch is never due";
  policy.add(1, 100 * kMs);
  policy.add(1, 108 * kMs);
  EXPECT_EQ(policy.due_ns(), 110 * kMs) << "the first observation sets the deadline";
  EXPECT_FALSE(policy.due(109 * kMs));
  EXPECT_TRUE(policy.due(110 * kMs));
  policy.written();
  EXPECT_FALSE(policy.due(200 * kMs));
  policy.add(1, 200 * kMs);
  EXPECT_EQ(policy.due_ns(), 210 * kMs);
}

TEST(BatchPolicy, OneObservationPerBatchWritesEachAtOnce) {
  BatchPolicy policy({.max_observations = 1, .max_wait_ns = 0});
  EXPECT_TRUE(policy.add(0, 0));
  policy.written();
  EXPECT_TRUE(policy.add(3, 1));
}

}  // namespace
}  // namespace slam::gateway

namespace slam::gateway {
namespace {

TEST(BatchPolicy, SaysWhatStillGoesInBeforeItIsFull) {
  BatchPolicy policy({.max_observations = 4, .max_points = 100, .max_wait_ns = 10});
  EXPECT_EQ(policy.observations_left(), 4u);
  EXPECT_EQ(policy.points_left(), 100u);
  policy.add(30, 0);
  policy.add(60, 1);
  EXPECT_EQ(policy.observations_left(), 2u);
  EXPECT_EQ(policy.points_left(), 10u);
  policy.written();
  EXPECT_EQ(policy.observations_left(), 4u);
  EXPECT_EQ(policy.points_left(), 100u);
}

}  // namespace
}  // namespace slam::gateway
