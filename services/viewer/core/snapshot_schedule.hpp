#pragma once
// When a headless viewer writes its periodic snapshots and under which names: DIR/snapshot-NNNN.png
// numbered on from the highest already in DIR (a restart never overwrites an earlier run), plus
// DIR/latest.png, each written through a hidden temp name and renamed so a reader never sees half a
// file. Pure time and name logic, so it is tested without a window or a disk.
#include <cstdint>
#include <optional>
#include <string>

namespace slam::viewer {

// "snapshot-0007.png" (at least four digits; 10000 and beyond simply get longer).
std::string snapshot_file_name(uint32_t index);
// The index in a snapshot file name, or nothing for any other name.
std::optional<uint32_t> parse_snapshot_file_name(const std::string& name);

struct SnapshotNames {
  uint32_t index = 0;
  std::string path;         // DIR/snapshot-NNNN.png
  std::string temp_path;    // DIR/.snapshot-NNNN.png.tmp, renamed to `path`
  std::string latest;       // DIR/latest.png
  std::string latest_temp;  // DIR/.latest.png.tmp, renamed to `latest`
  std::string expired;      // a numbered snapshot to delete (beyond --snapshot-keep), or empty
};

class SnapshotSchedule {
 public:
  // `first_index`: number of the first snapshot; `keep`: numbered snapshots kept (0 keeps all).
  SnapshotSchedule(std::string dir, double period_s, uint32_t first_index, uint32_t keep);

  // The first snapshot is due one period after `now_ns` (the window has nothing to show before).
  void start(int64_t now_ns);
  bool due(int64_t now_ns) const { return started_ && now_ns >= next_due_ns_; }
  // Names for the snapshot taken now; schedules the next one. A late call (a stalled frame) does
  // not cause a burst: the next one is due a period after a snapshot that was over a period late.
  SnapshotNames take(int64_t now_ns);
  // No snapshot this period (nothing to show, e.g. a minimised window): the next is due a period on.
  void skip(int64_t now_ns);

  uint32_t next_index() const { return next_index_; }
  const std::string& dir() const { return dir_; }

 private:
  std::string in_dir(const std::string& name) const;

  std::string dir_;
  int64_t period_ns_;
  uint32_t next_index_;
  uint32_t keep_;
  bool started_ = false;
  int64_t next_due_ns_ = 0;
};

}  // namespace slam::viewer
