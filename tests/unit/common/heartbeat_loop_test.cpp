#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "common/core/service_identity.hpp"

namespace slam {
namespace {

struct Written {
  std::string service;
  std::string instance_id;
  uint32_t state;
  std::vector<std::pair<std::string, int64_t>> counters;
};

// A period far longer than the test, so only the writes the test causes happen.
constexpr auto kNeverTicks = std::chrono::hours(1);

TEST(HeartbeatLoop, WritesOnceAtStartWithStateStartingAndTheCounters) {
  Counters counters;
  counters.get("messages") = 7;
  std::vector<Written> written;
  HeartbeatLoop loop("mapper", counters, kNeverTicks, [&](const HeartbeatContent& c) {
    written.push_back({c.identity.service, c.identity.instance_id, c.state, c.counters});
  });
  ASSERT_EQ(written.size(), 1u);
  EXPECT_EQ(written[0].service, "mapper");
  EXPECT_EQ(written[0].instance_id, loop.identity().host + ":" + std::to_string(getpid()));
  EXPECT_EQ(written[0].state, 0u);
  ASSERT_EQ(written[0].counters.size(), 1u);
  EXPECT_EQ(written[0].counters[0].first, "messages");
  EXPECT_EQ(written[0].counters[0].second, 7);
}

TEST(HeartbeatLoop, AStateChangeIsWrittenAtOnceWithTheCurrentCounters) {
  Counters counters;
  auto& messages = counters.get("messages");
  std::vector<Written> written;
  HeartbeatLoop loop("gateway", counters, kNeverTicks, [&](const HeartbeatContent& c) {
    written.push_back({c.identity.service, c.identity.instance_id, c.state, c.counters});
  });
  messages = 3;
  loop.set_state(1);
  ASSERT_EQ(written.size(), 2u);
  EXPECT_EQ(written[1].state, 1u);
  EXPECT_EQ(written[1].counters[0].second, 3);
}

TEST(HeartbeatLoop, KeepsWritingEveryPeriodUntilDestroyed) {
  Counters counters;
  std::mutex mutex;
  int writes = 0;
  {
    HeartbeatLoop loop("planner", counters, std::chrono::milliseconds(30), [&](const HeartbeatContent&) {
      std::lock_guard lock(mutex);
      ++writes;
    });
    // Wait (bounded) for two periodic writes beside the one at start.
    for (int i = 0; i < 500; ++i) {
      {
        std::lock_guard lock(mutex);
        if (writes >= 3) break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  std::lock_guard lock(mutex);
  const int after_destruction = writes;
  EXPECT_GE(after_destruction, 3);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_EQ(writes, after_destruction);
}

}  // namespace
}  // namespace slam
