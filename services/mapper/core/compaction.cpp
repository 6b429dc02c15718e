// Compaction: which rows, and the baseline that replaces them (see compaction.hpp).
#include "mapper/core/compaction.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mapper/core/store_baseline.hpp"

namespace slam::mapper {
namespace {

constexpr double kNsPerS = 1e9;
constexpr double kSPerDay = 86400.0;
constexpr double kBytesPerMb = 1024.0 * 1024.0;

}  // namespace

Status validate(const CompactionOptions& o) {
  if (!(o.retention_days >= 0.0) || !std::isfinite(o.retention_days))
    return Error{"store.retention_days: must be >= 0 (0: no compaction by age), got " +
                 std::to_string(o.retention_days)};
  if (!(o.max_mb >= 0.0) || !std::isfinite(o.max_mb))
    return Error{"store.max_mb: must be >= 0 (0: no bound), got " + std::to_string(o.max_mb)};
  if (!(o.min_age_s >= 0.0) || !std::isfinite(o.min_age_s))
    return Error{"store.min_age_s: must be >= 0, got " + std::to_string(o.min_age_s)};
  if (!(o.interval_s > 0.0) || !std::isfinite(o.interval_s))
    return Error{"store.compact_interval_s: must be > 0, got " + std::to_string(o.interval_s)};
  return Status::ok();
}

std::optional<CompactionPlan> plan_compaction(const FootprintIndex& index, int64_t now_stamp_ns,
                                              int64_t used_bytes, int64_t last_global_move_ns,
                                              const CompactionOptions& o) {
  const auto groups = index.groups();
  if (groups.empty()) return std::nullopt;
  const auto before = [&](double seconds) {
    return now_stamp_ns - static_cast<int64_t>(std::min(seconds * kNsPerS, 9e18));
  };
  const int64_t settled = before(o.min_age_s);
  if (last_global_move_ns > settled) return std::nullopt;  // everything may have moved just now
  const bool over_size = o.max_mb > 0.0 && static_cast<double>(used_bytes) > o.max_mb * kBytesPerMb;
  int64_t cut = std::numeric_limits<int64_t>::min();  // first seen at or before: old enough
  if (over_size)
    cut = settled;
  else if (o.retention_days > 0.0)
    cut = std::min(before(o.retention_days * kSPerDay), settled);
  else
    return std::nullopt;

  int64_t last = 0;
  for (const FootprintGroup& g : groups) last = std::max(last, g.last_row);
  int64_t through = last - 1;  // one row stays: row ids never restart below the baseline
  for (const FootprintGroup& g : groups)
    if (g.first_stamp_ns > cut || g.moved_stamp_ns > settled) through = std::min(through, g.first_row - 1);
  CompactionPlan plan;
  plan.through_row = through;
  bool due = false;
  for (const FootprintGroup& g : groups) {
    due = due || g.first_row <= through;
    plan.groups += g.last_row <= through ? 1 : 0;
  }
  if (!due) return std::nullopt;
  plan.why = over_size ? "store " + std::to_string(used_bytes / (1024 * 1024)) + " MB over --store-max-mb"
                       : "raw observations older than " + std::to_string(o.retention_days) + " days";
  return plan;
}

Result<CompactionReport> compact_store(const GridConfig& config, ObservationStore& store,
                                       const KeyframeCorrections& corrections, int64_t through_row) {
  CompactionReport report;
  report.through_row = through_row;
  auto grid = rebuild_through(config, store, through_row, corrections, &report.stats);
  if (!grid) return grid.error();
  const Baseline baseline = baseline_of(*grid, through_row);
  auto deleted = store.compact(baseline);
  if (!deleted) return deleted.error();
  report.rows_deleted = *deleted;
  report.tiles = static_cast<int64_t>(baseline.tiles.size());
  return report;
}

}  // namespace slam::mapper
