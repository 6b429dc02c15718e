// Snapshot timing and file names (see snapshot_schedule.hpp).
#include "viewer/core/snapshot_schedule.hpp"

#include <cmath>
#include <cstdio>
#include <string_view>
#include <utility>

namespace slam::viewer {

std::string snapshot_file_name(uint32_t index) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "snapshot-%04u.png", index);
  return buf;
}

std::optional<uint32_t> parse_snapshot_file_name(const std::string& name) {
  constexpr std::string_view prefix = "snapshot-", suffix = ".png";
  if (name.size() <= prefix.size() + suffix.size() || name.compare(0, prefix.size(), prefix) != 0 ||
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
    return std::nullopt;
  const std::string digits = name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  if (digits.size() > 9) return std::nullopt;  // fits uint32_t
  uint32_t value = 0;
  for (char c : digits) {
    if (c < '0' || c > '9') return std::nullopt;
    value = value * 10 + static_cast<uint32_t>(c - '0');
  }
  return value;
}

SnapshotSchedule::SnapshotSchedule(std::string dir, double period_s, uint32_t first_index, uint32_t keep)
    : dir_(std::move(dir)),
      period_ns_(static_cast<int64_t>(std::llround(period_s * 1e9))),
      next_index_(first_index),
      keep_(keep) {}

void SnapshotSchedule::start(int64_t now_ns) {
  started_ = true;
  next_due_ns_ = now_ns + period_ns_;
}

std::string SnapshotSchedule::in_dir(const std::string& name) const {
  if (dir_.empty()) return name;
  return dir_.back() == '/' ? dir_ + name : dir_ + "/" + name;
}

SnapshotNames SnapshotSchedule::take(int64_t now_ns) {
  SnapshotNames n;
  n.index = next_index_++;
  const std::string file = snapshot_file_name(n.index);
  n.path = in_dir(file);
  n.temp_path = in_dir("." + file + ".tmp");
  n.latest = in_dir("latest.png");
  n.latest_temp = in_dir(".latest.png.tmp");
  if (keep_ > 0 && n.index > keep_) n.expired = in_dir(snapshot_file_name(n.index - keep_));
  skip(now_ns);
  return n;
}

void SnapshotSchedule::skip(int64_t now_ns) {
  next_due_ns_ += period_ns_;
  if (next_due_ns_ <= now_ns) next_due_ns_ = now_ns + period_ns_;
}

}  // namespace slam::viewer
