// TrafficQueue and TokenBucket: truncation, bounds, rate, drop accounting through seq gaps.
#include "gateway/core/traffic_queue.hpp"

#include <gtest/gtest.h>

#include <string>
#include <thread>
#include <vector>

namespace slam::gateway {
namespace {

using namespace std::chrono_literals;

std::span<const std::uint8_t> bytes(const std::string& s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

TEST(TokenBucket, AllowsTheBurstThenTheRate) {
  TokenBucket bucket(10.0, 3.0);  // 10 per second, 3 saved up
  int allowed = 0;
  for (int i = 0; i < 10; ++i) allowed += bucket.take(0) ? 1 : 0;
  EXPECT_EQ(allowed, 3);
  EXPECT_FALSE(bucket.take(50'000'000));  // half a token after 50 ms
  EXPECT_TRUE(bucket.take(100'000'000));  // one token after 100 ms
  EXPECT_FALSE(bucket.take(100'000'000));
}

TEST(TrafficQueue, CopiesAndTruncatesToTheIdlBounds) {
  TrafficQueue queue(8, 1000.0);
  const std::string topic(300, 't');
  const std::string payload(2000, 'p');
  ASSERT_TRUE(queue.push(TrafficDirection::Outbound, topic, bytes(payload), 42, 0));
  auto batch = queue.make_batch(4);
  ASSERT_EQ(queue.pop(batch, 0ms), 1u);
  EXPECT_EQ(batch[0].seq, 1u);
  EXPECT_EQ(batch[0].stamp_ns, 42);
  EXPECT_EQ(batch[0].direction, TrafficDirection::Outbound);
  EXPECT_EQ(batch[0].topic.size(), kTrafficTopicBytes);
  EXPECT_EQ(batch[0].payload.size(), kTrafficPayloadBytes);
  EXPECT_EQ(batch[0].payload_size, 2000u);
}

TEST(TrafficQueue, AFullRingDropsAndSequenceNumbersShowTheGap) {
  TrafficQueue queue(2, 1e9);
  EXPECT_TRUE(queue.push(TrafficDirection::Inbound, "a", {}, 0, 0));
  EXPECT_TRUE(queue.push(TrafficDirection::Inbound, "b", {}, 0, 0));
  EXPECT_FALSE(queue.push(TrafficDirection::Inbound, "c", {}, 0, 0));
  auto batch = queue.make_batch(8);
  ASSERT_EQ(queue.pop(batch, 0ms), 2u);
  EXPECT_EQ(batch[0].topic, "a");
  EXPECT_EQ(batch[1].topic, "b");
  EXPECT_TRUE(queue.push(TrafficDirection::Inbound, "d", {}, 0, 0));
  ASSERT_EQ(queue.pop(batch, 0ms), 1u);
  EXPECT_EQ(batch[0].topic, "d");
  EXPECT_EQ(batch[0].seq, 4u) << "the dropped 'c' was seq 3";
}

TEST(TrafficQueue, RateLimitDrops) {
  TrafficQueue queue(1000, 100.0);  // burst of 10
  int accepted = 0;
  for (int i = 0; i < 100; ++i) accepted += queue.push(TrafficDirection::Inbound, "t", {}, 0, 0) ? 1 : 0;
  EXPECT_EQ(accepted, 10);
  EXPECT_TRUE(queue.push(TrafficDirection::Inbound, "t", {}, 0, 10'000'000));  // 10 ms later: one more
}

TEST(TrafficQueue, ZeroRateTurnsTheLogOff) {
  TrafficQueue queue(10, 0.0);
  EXPECT_FALSE(queue.push(TrafficDirection::Inbound, "t", {}, 0, 0));
}

TEST(TrafficQueue, PopWaitsForAFullBatchAndCloseWakesIt) {
  TrafficQueue queue(8, 1000.0);
  auto batch = queue.make_batch(4);
  queue.push(TrafficDirection::Inbound, "early", {}, 0, 0);
  EXPECT_EQ(queue.pop(batch, 10ms), 1u);  // less than a batch: taken when the wait times out
  std::thread producer([&] {
    std::this_thread::sleep_for(20ms);
    for (int i = 0; i < 5; ++i) queue.push(TrafficDirection::Inbound, "late", {}, 0, 0);
  });
  // The fourth record wakes the waiting pop, which takes one batch (the fifth waits for the next).
  const auto waiting_since = std::chrono::steady_clock::now();
  const size_t taken = queue.pop(batch, 5s);
  EXPECT_EQ(taken, 4u);
  EXPECT_LT(std::chrono::steady_clock::now() - waiting_since, 4s);  // woken, not timed out
  producer.join();
  EXPECT_EQ(taken + queue.pop(batch, 0ms), 5u);
  std::thread closer([&] {
    std::this_thread::sleep_for(20ms);
    queue.close();
  });
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(queue.pop(batch, 5s), 0u);
  EXPECT_LT(std::chrono::steady_clock::now() - start, 4s);
  closer.join();
  EXPECT_FALSE(queue.push(TrafficDirection::Inbound, "after", {}, 0, 0));
}

}  // namespace
}  // namespace slam::gateway
