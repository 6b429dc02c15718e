// The snapshot writer thread and directory: numbering continues after earlier runs, a job ends as
// a numbered PNG plus latest.png with no temp file left, retention deletes the oldest, errors are
// counted rather than fatal, and the destructor writes what is still pending.
#include "viewer/core/snapshot_writer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "temp_dir.hpp"

namespace slam::viewer {
namespace {

namespace fs = std::filesystem;

SnapshotJob job(SnapshotSchedule& schedule, int64_t now_ns) {
  SnapshotJob j;
  j.names = schedule.take(now_ns);
  j.image = {2, 2, true, std::vector<uint8_t>(12, 200)};
  j.summary = "test";
  return j;
}

std::vector<std::string> listing(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(SnapshotWriter, PrepareCreatesTheDirectoryAndNumbersAfterEarlierRuns) {
  testkit::TempDir dir("snapshot-writer");
  auto first = prepare_snapshot_dir((dir.path() / "snaps").string());
  ASSERT_TRUE(first) << first.message();
  EXPECT_EQ(*first, 1u);
  for (const char* name : {"snapshot-0003.png", "snapshot-0017.png", "latest.png", "notes.txt"})
    std::ofstream(dir.path() / "snaps" / name) << "x";
  first = prepare_snapshot_dir((dir.path() / "snaps").string());
  ASSERT_TRUE(first) << first.message();
  EXPECT_EQ(*first, 18u);
}

TEST(SnapshotWriter, PrepareNamesAPathThatIsNotADirectory) {
  testkit::TempDir dir("snapshot-writer");
  fs::create_directories(dir.path());
  std::ofstream(dir.path() / "file") << "x";
  auto r = prepare_snapshot_dir((dir.path() / "file").string());
  ASSERT_FALSE(r);
  EXPECT_NE(r.message().find("--snapshot-dir"), std::string::npos) << r.message();
}

TEST(SnapshotWriter, WritesNumberedAndLatestAndHonoursKeep) {
  testkit::TempDir dir("snapshot-writer");
  ASSERT_TRUE(prepare_snapshot_dir(dir.path().string()));
  SnapshotSchedule schedule(dir.path().string(), 1.0, 1, 2);
  schedule.start(0);
  SnapshotWriter writer;
  for (int64_t i = 1; i <= 3; ++i) {
    ASSERT_TRUE(writer.submit(job(schedule, i * 1'000'000'000)));
    writer.wait_idle();
  }
  EXPECT_EQ(writer.written(), 3u);
  EXPECT_EQ(writer.failed(), 0u);
  EXPECT_EQ(listing(dir.path()),
            (std::vector<std::string>{"latest.png", "snapshot-0002.png", "snapshot-0003.png"}));
  EXPECT_EQ(fs::file_size(dir.path() / "latest.png"), fs::file_size(dir.path() / "snapshot-0003.png"));
}

TEST(SnapshotWriter, AFailedWriteIsCountedAndTheWriterCarriesOn) {
  testkit::TempDir dir("snapshot-writer");
  SnapshotSchedule missing((dir.path() / "gone").string(), 1.0, 1, 0);
  SnapshotSchedule good(dir.path().string(), 1.0, 1, 0);
  ASSERT_TRUE(prepare_snapshot_dir(dir.path().string()));
  SnapshotWriter writer;
  ASSERT_TRUE(writer.submit(job(missing, 1)));
  writer.wait_idle();
  ASSERT_TRUE(writer.submit(job(good, 1)));
  writer.wait_idle();
  EXPECT_EQ(writer.failed(), 1u);
  EXPECT_EQ(writer.written(), 1u);
}

TEST(SnapshotWriter, DestructorWritesThePendingJob) {
  testkit::TempDir dir("snapshot-writer");
  ASSERT_TRUE(prepare_snapshot_dir(dir.path().string()));
  SnapshotSchedule schedule(dir.path().string(), 1.0, 5, 0);
  {
    SnapshotWriter writer;
    writer.submit(job(schedule, 1));
  }
  EXPECT_TRUE(fs::exists(dir.path() / "snapshot-0005.png"));
  EXPECT_TRUE(fs::exists(dir.path() / "latest.png"));
}

}  // namespace
}  // namespace slam::viewer
