#include "common/core/request_retry.hpp"

#include <gtest/gtest.h>

#include <set>
#include <vector>

namespace slam {
namespace {

using namespace std::chrono_literals;
using Clock = RetrySchedule::Clock;

// Every time the schedule says "send" when polled each millisecond from the start to `until`.
std::vector<std::chrono::milliseconds> sends(const RetryPolicy& policy, std::chrono::milliseconds until) {
  const Clock::time_point start{};
  RetrySchedule schedule(policy, start);
  std::vector<std::chrono::milliseconds> at;
  for (auto t = 0ms; t <= until; t += 1ms)
    if (schedule.due(start + t)) at.push_back(t);
  return at;
}

TEST(RetrySchedule, SendsAtOnceThenAfterDoublingIntervalsUpToTheMaximum) {
  const RetryPolicy policy{100ms, 400ms, 2000ms};
  const std::vector<std::chrono::milliseconds> expected{0ms, 100ms, 300ms, 700ms, 1100ms, 1500ms, 1900ms};
  EXPECT_EQ(sends(policy, 3000ms), expected);
}

TEST(RetrySchedule, NothingIsDueAtOrAfterTheDeadline) {
  const Clock::time_point start{};
  RetrySchedule schedule(RetryPolicy{100ms, 100ms, 250ms}, start);
  EXPECT_FALSE(schedule.expired(start + 249ms));
  EXPECT_TRUE(schedule.expired(start + 250ms));
  EXPECT_FALSE(schedule.due(start + 250ms));
  EXPECT_EQ(schedule.deadline(), start + 250ms);
}

TEST(RetrySchedule, EachDueTimeAnswersOnce) {
  const Clock::time_point start{};
  RetrySchedule schedule(RetryPolicy{}, start);
  EXPECT_TRUE(schedule.due(start));
  EXPECT_FALSE(schedule.due(start));
  EXPECT_EQ(schedule.next_send(), start + RetryPolicy{}.first_interval);
}

TEST(RequestIdSource, IdsAreNonZeroAndDistinctWithinAndAcrossSources) {
  RequestIdSource a;
  RequestIdSource b;
  std::set<uint64_t> seen;
  for (int i = 0; i < 1000; ++i) {
    for (uint64_t id : {a.next(), b.next()}) {
      EXPECT_NE(id, 0u);
      EXPECT_TRUE(seen.insert(id).second) << "id " << id << " twice";
    }
  }
}

}  // namespace
}  // namespace slam
