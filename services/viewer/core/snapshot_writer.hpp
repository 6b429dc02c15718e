#pragma once
// Writes periodic snapshots off the render thread: the frame loop only reads the pixels back and
// hands them over; PNG encoding (tens of milliseconds for a full window) and the file writes happen
// here. One job at a time: a snapshot that arrives while the previous one is still being written is
// dropped and counted, so a slow disk can never queue up memory or stall frames.
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "common/core/result.hpp"
#include "viewer/core/png_file.hpp"
#include "viewer/core/snapshot_schedule.hpp"

namespace slam::viewer {

struct SnapshotJob {
  SnapshotNames names;
  RgbImage image;
  std::string summary;  // appended to the log line, e.g. "3 robots, 120000 points"
};

// The first free snapshot index in `dir` (one past the highest snapshot-N.png; 1 when none), after
// creating `dir` when it is missing. The error names the directory and the reason.
Result<uint32_t> prepare_snapshot_dir(const std::string& dir);

class SnapshotWriter {
 public:
  SnapshotWriter();
  // Writes the job still pending, then stops the thread.
  ~SnapshotWriter();
  SnapshotWriter(const SnapshotWriter&) = delete;
  SnapshotWriter& operator=(const SnapshotWriter&) = delete;

  // False (and the job is dropped) when the previous job is still being written.
  bool submit(SnapshotJob&& job);
  // Blocks until nothing is pending or being written (tests, shutdown).
  void wait_idle();

  uint64_t written() const;
  uint64_t failed() const;
  uint64_t dropped() const;

 private:
  void run();
  static Status write(const SnapshotJob& job);

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable idle_;
  std::optional<SnapshotJob> pending_;
  bool busy_ = false;
  bool stopping_ = false;
  uint64_t written_ = 0, failed_ = 0, dropped_ = 0;
  std::thread thread_;  // last: starts after every other member exists
};

}  // namespace slam::viewer
