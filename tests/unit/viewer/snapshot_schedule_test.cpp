// Snapshot names and timing: numbering, temp names beside the final ones, one period between
// snapshots without bursts after a stall, retention.
#include "viewer/core/snapshot_schedule.hpp"

#include <gtest/gtest.h>

namespace slam::viewer {
namespace {

constexpr int64_t kSecond = 1'000'000'000;

TEST(SnapshotSchedule, FileNamesRoundTrip) {
  EXPECT_EQ(snapshot_file_name(7), "snapshot-0007.png");
  EXPECT_EQ(snapshot_file_name(12345), "snapshot-12345.png");
  EXPECT_EQ(parse_snapshot_file_name("snapshot-0007.png"), 7u);
  EXPECT_EQ(parse_snapshot_file_name("snapshot-12345.png"), 12345u);
  for (const char* other : {"latest.png", "snapshot-.png", "snapshot-12a.png", ".snapshot-0001.png.tmp",
                            "snapshot-0001.png.tmp", "snapshot-9999999999.png", "shot-0001.png"})
    EXPECT_FALSE(parse_snapshot_file_name(other)) << other;
}

TEST(SnapshotSchedule, NothingIsDueBeforeStartAndTheFirstComesOnePeriodLater) {
  SnapshotSchedule s("out", 10.0, 1, 0);
  EXPECT_FALSE(s.due(100 * kSecond));
  s.start(5 * kSecond);
  EXPECT_FALSE(s.due(5 * kSecond));
  EXPECT_FALSE(s.due(15 * kSecond - 1));
  EXPECT_TRUE(s.due(15 * kSecond));
}

TEST(SnapshotSchedule, NamesAreNumberedWithTempNamesInTheSameDirectory) {
  SnapshotSchedule s("run/snapshots/", 1.0, 42, 0);
  s.start(0);
  const SnapshotNames n = s.take(kSecond);
  EXPECT_EQ(n.index, 42u);
  EXPECT_EQ(n.path, "run/snapshots/snapshot-0042.png");
  EXPECT_EQ(n.temp_path, "run/snapshots/.snapshot-0042.png.tmp");
  EXPECT_EQ(n.latest, "run/snapshots/latest.png");
  EXPECT_EQ(n.latest_temp, "run/snapshots/.latest.png.tmp");
  EXPECT_TRUE(n.expired.empty());
  EXPECT_EQ(s.take(2 * kSecond).path, "run/snapshots/snapshot-0043.png");
  EXPECT_EQ(s.next_index(), 44u);
}

TEST(SnapshotSchedule, KeepsThePeriodAndSkipsMissedSlotsInsteadOfBursting) {
  SnapshotSchedule s("d", 10.0, 1, 0);
  s.start(0);
  // Taken 0.2 s late: the next is still due at 20 s, so the rate does not drift.
  s.take(10 * kSecond + kSecond / 5);
  EXPECT_FALSE(s.due(20 * kSecond - 1));
  EXPECT_TRUE(s.due(20 * kSecond));
  // A 35 s stall: one snapshot now, the next a full period later, not three in a row.
  s.take(55 * kSecond);
  EXPECT_FALSE(s.due(55 * kSecond));
  EXPECT_FALSE(s.due(65 * kSecond - 1));
  EXPECT_TRUE(s.due(65 * kSecond));
}

TEST(SnapshotSchedule, ASkippedPeriodUsesNoNumber) {
  SnapshotSchedule s("d", 1.0, 3, 0);
  s.start(0);
  s.skip(kSecond);
  EXPECT_FALSE(s.due(2 * kSecond - 1));
  EXPECT_TRUE(s.due(2 * kSecond));
  EXPECT_EQ(s.take(2 * kSecond).index, 3u);
}

TEST(SnapshotSchedule, KeepDeletesTheSnapshotThatFellOutOfTheWindow) {
  SnapshotSchedule s("d", 1.0, 1, 3);
  s.start(0);
  for (int64_t i = 1; i <= 3; ++i) EXPECT_TRUE(s.take(i * kSecond).expired.empty());
  EXPECT_EQ(s.take(4 * kSecond).expired, "d/snapshot-0001.png");
  EXPECT_EQ(s.take(5 * kSecond).expired, "d/snapshot-0002.png");
}

}  // namespace
}  // namespace slam::viewer
