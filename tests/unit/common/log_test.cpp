// Rate-limited logging and counters: what keeps a flood of bad input from flooding the log.
#include "common/core/log.hpp"

#include <gtest/gtest.h>
#include <spdlog/sinks/ostream_sink.h>

#include <sstream>
#include <thread>

#include "common/core/counters.hpp"

namespace slam {
namespace {

TEST(RateLimiter, OneLinePerKeyPerIntervalAndCountsTheRest) {
  RateLimiter limiter(std::chrono::milliseconds(50));
  uint64_t suppressed = 99;
  EXPECT_TRUE(limiter.allow("r1:bad_length", &suppressed));
  EXPECT_EQ(suppressed, 0u);
  EXPECT_FALSE(limiter.allow("r1:bad_length", &suppressed));
  EXPECT_FALSE(limiter.allow("r1:bad_length", &suppressed));
  EXPECT_TRUE(limiter.allow("r2:bad_length", &suppressed)) << "keys are independent";
  std::this_thread::sleep_for(std::chrono::milliseconds(60));
  EXPECT_TRUE(limiter.allow("r1:bad_length", &suppressed));
  EXPECT_EQ(suppressed, 2u);
}

TEST(RateLimiter, ManyDistinctKeysStayBounded) {
  RateLimiter limiter(std::chrono::hours(1));
  uint64_t suppressed = 0;
  for (int i = 0; i < 20000; ++i) EXPECT_TRUE(limiter.allow("robot-" + std::to_string(i), &suppressed));
}

TEST(RateLimitedLog, TailCountsTheLinesSuppressedSinceTheLastOneWritten) {
  RateLimitedLog log(std::chrono::seconds(1));
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_EQ(log.admit("write:slam/map", t0), "") << "nothing suppressed yet: no tail";
  EXPECT_EQ(log.admit("write:slam/map", t0 + std::chrono::milliseconds(10)), std::nullopt);
  EXPECT_EQ(log.admit("write:slam/map", t0 + std::chrono::milliseconds(20)), std::nullopt);
  EXPECT_EQ(log.admit("write:slam/state", t0 + std::chrono::milliseconds(30)), "") << "keys are independent";
  EXPECT_EQ(log.admit("write:slam/map", t0 + std::chrono::seconds(2)), " (2 similar suppressed)");
  EXPECT_EQ(log.admit("write:slam/map", t0 + std::chrono::seconds(4)), "") << "the count starts again";
}

TEST(RateLimitedLog, WarnWritesTheFormattedLineOncePerInterval) {
  std::ostringstream out;
  auto logger = std::make_shared<spdlog::logger>("rate_limited_log_test",
                                                 std::make_shared<spdlog::sinks::ostream_sink_mt>(out));
  logger->set_pattern("%l %v");
  const auto previous = spdlog::default_logger();
  spdlog::set_default_logger(logger);

  RateLimitedLog log(std::chrono::hours(1));
  const bool first = log.warn("r1:bad_length", "robot '{}': bad length {}", "r1", 7);
  const bool second = log.warn("r1:bad_length", "robot '{}': bad length {}", "r1", 8);
  spdlog::set_default_logger(previous);

  EXPECT_TRUE(first);
  EXPECT_FALSE(second);
  EXPECT_EQ(out.str(), "warning robot 'r1': bad length 7\n");
}

TEST(Counters, SameNameSameCounterAndSnapshotInOrder) {
  Counters counters;
  auto& a = counters.get("messages_in");
  auto& b = counters.get("rejected_bad_length");
  bump(a, 3);
  bump(counters.get("messages_in"));
  bump(b);
  const auto snap = counters.snapshot();
  ASSERT_EQ(snap.size(), 2u);
  EXPECT_EQ(snap[0].first, "messages_in");
  EXPECT_EQ(snap[0].second, 4);
  EXPECT_EQ(snap[1].second, 1);
}

TEST(Logging, RejectsUnknownLevel) {
  EXPECT_TRUE(setup_logging("test_ok", "debug"));
  EXPECT_FALSE(setup_logging("test_bad", "loud"));
}

}  // namespace
}  // namespace slam
