// Ownership: the live set from heartbeats and the rendezvous choice every instance makes alike.
#include "common/core/ownership.hpp"

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

namespace slam {
namespace {

constexpr std::int64_t kSecond = 1'000'000'000;
constexpr OwnershipConfig kConfig{kSecond, 2 * kSecond};
constexpr std::int64_t kWarm = 10 * kSecond;  // every instance is past its warm-up

std::vector<std::string> robot_ids(int n) {
  std::vector<std::string> ids;
  for (int i = 0; i < n; ++i) ids.push_back("robot-" + std::to_string(i));
  return ids;
}

// An instance that has heard every one of `peers` at `at`.
Ownership instance(const std::string& self, const std::vector<std::string>& peers, std::int64_t at = kWarm) {
  Ownership o(self, 0, kConfig);
  for (const std::string& p : peers) o.heard(p, at);
  return o;
}

std::map<std::string, std::string> owners(const Ownership& o, const std::vector<std::string>& keys,
                                          std::int64_t now) {
  std::map<std::string, std::string> out;
  for (const std::string& k : keys) out[k] = o.owner_of(k, now);
  return out;
}

TEST(Ownership, EveryInstanceChoosesTheSameOwner) {
  const std::vector<std::string> all{"host-a:11", "host-b:22", "host-c:33"};
  const Ownership a = instance(all[0], {all[1], all[2]});
  const Ownership b = instance(all[1], {all[2], all[0]});
  const Ownership c = instance(all[2], {all[0], all[1]});
  for (const std::string& id : robot_ids(500)) {
    const std::string& owner = a.owner_of(id, kWarm);
    EXPECT_EQ(b.owner_of(id, kWarm), owner) << id;
    EXPECT_EQ(c.owner_of(id, kWarm), owner) << id;
    // Exactly one of them claims it.
    EXPECT_EQ(int(a.owns(id, kWarm)) + int(b.owns(id, kWarm)) + int(c.owns(id, kWarm)), 1) << id;
  }
}

TEST(Ownership, WeightIsAFixedFunctionOfInstanceAndKey) {
  EXPECT_EQ(rendezvous_weight("host-a:11", "r1"), rendezvous_weight("host-a:11", "r1"));
  EXPECT_NE(rendezvous_weight("host-a:11", "r1"), rendezvous_weight("host-a:11", "r2"));
  EXPECT_NE(rendezvous_weight("ab", "c"), rendezvous_weight("a", "bc"));
}

TEST(Ownership, KeysSpreadEvenlyOverInstances) {
  const std::vector<std::string> all{"gw-1:100", "gw-2:100", "gw-3:100", "gw-4:100"};
  const Ownership a = instance(all[0], {all[1], all[2], all[3]});
  std::map<std::string, int> share;
  const auto ids = robot_ids(4000);
  for (const std::string& id : ids) ++share[a.owner_of(id, kWarm)];
  ASSERT_EQ(share.size(), all.size());
  for (const auto& [who, n] : share) {
    // 1000 expected each; 4 standard deviations is about +-110.
    EXPECT_GT(n, 850) << who;
    EXPECT_LT(n, 1150) << who;
  }
}

TEST(Ownership, OnlyTheDeadInstancesKeysMoveWhenItFallsSilent) {
  Ownership a = instance("gw-a:1", {"gw-b:2", "gw-c:3"});
  const auto ids = robot_ids(1000);
  const auto before = owners(a, ids, kWarm);
  // gw-c keeps beating, gw-b falls silent.
  a.heard("gw-c:3", kWarm + kSecond / 2);
  const std::int64_t later = kWarm + kSecond + kSecond / 4;
  std::vector<std::string> gone;
  EXPECT_EQ(a.expire(later, &gone), 1u);
  EXPECT_EQ(gone, std::vector<std::string>{"gw-b:2"});
  const auto after = owners(a, ids, later);
  int moved = 0;
  for (const std::string& id : ids) {
    if (before.at(id) == "gw-b:2") {
      EXPECT_NE(after.at(id), "gw-b:2") << id;
      ++moved;
    } else {
      EXPECT_EQ(after.at(id), before.at(id)) << id;
    }
  }
  EXPECT_GT(moved, 250);  // about a third
}

TEST(Ownership, ASilentPeerCountsAsGoneBeforeItIsExpired) {
  const Ownership a = instance("gw-a:1", {"gw-b:2"});
  const auto ids = robot_ids(200);
  const std::int64_t late = kWarm + kSecond + 1;
  for (const std::string& id : ids) EXPECT_TRUE(a.owns(id, late)) << id;
}

TEST(Ownership, AJoiningInstanceTakesOnlyItsShare) {
  Ownership a = instance("gw-a:1", {"gw-b:2"});
  const auto ids = robot_ids(1000);
  const auto before = owners(a, ids, kWarm);
  EXPECT_TRUE(a.heard("gw-new:9", kWarm));
  EXPECT_FALSE(a.heard("gw-new:9", kWarm));  // known already
  const auto after = owners(a, ids, kWarm);
  int taken = 0;
  for (const std::string& id : ids) {
    if (after.at(id) == before.at(id)) continue;
    EXPECT_EQ(after.at(id), "gw-new:9") << id << " moved between old instances";
    ++taken;
  }
  EXPECT_GT(taken, 250);  // about a third
  EXPECT_LT(taken, 420);
}

TEST(Ownership, ANewcomerOwnsNothingDuringItsWarmUp) {
  const std::int64_t start = 100 * kSecond;
  Ownership fresh("gw-new:9", start, kConfig);
  const auto ids = robot_ids(100);
  // Alone as far as it knows: the owner of everything in its own view, yet it claims nothing.
  for (const std::string& id : ids) {
    EXPECT_EQ(fresh.owner_of(id, start + kSecond), "gw-new:9");
    EXPECT_FALSE(fresh.owns(id, start + kSecond)) << id;
  }
  for (const std::string& id : ids) EXPECT_TRUE(fresh.owns(id, start + 2 * kSecond)) << id;
}

TEST(Ownership, AStoppingPeerLeavesAtOnce) {
  Ownership a = instance("gw-a:1", {"gw-b:2"});
  EXPECT_EQ(a.live_count(), 2u);
  const std::uint64_t version = a.version();
  EXPECT_TRUE(a.left("gw-b:2"));
  EXPECT_FALSE(a.left("gw-b:2"));
  EXPECT_GT(a.version(), version);
  EXPECT_EQ(a.live(), std::vector<std::string>{"gw-a:1"});
  for (const std::string& id : robot_ids(50)) EXPECT_TRUE(a.owns(id, kWarm)) << id;
}

TEST(Ownership, AHeartbeatIsHeardUnlessItSaysStopping) {
  Ownership a = instance("gw-a:1", {});
  a.observe("gw-b:2", false, kWarm);
  EXPECT_EQ(a.live_count(), 2u);
  a.observe("gw-b:2", true, kWarm);
  EXPECT_EQ(a.live(), std::vector<std::string>{"gw-a:1"});
}

TEST(Ownership, TheOwnHeartbeatIsNotAPeer) {
  Ownership a("gw-a:1", 0, kConfig);
  EXPECT_FALSE(a.heard("gw-a:1", kWarm));
  EXPECT_EQ(a.live_count(), 1u);
}

}  // namespace
}  // namespace slam
