// Mapper: compaction of old observations into the store's baseline, on the worker like a rebuild
// (compaction.hpp). Planned on the loop from the footprint index at most every
// --store-compact-interval-s; while it runs, observations are integrated and kept aside, as during
// a rebuild, and stored once it lands (after the rows it removed: row ids only grow).
#include <utility>

#include "mapper/core/compaction.hpp"
#include "mapper/core/mapper.hpp"

namespace slam::mapper {

void Mapper::maybe_compact() {
  if (loop_now_ns_ < next_compaction_check_ns_) return;
  if (start_compaction(true) || !worker_.busy())
    next_compaction_check_ns_ = loop_now_ns_ + static_cast<int64_t>(options_.compaction.interval_s * 1e9);
}

bool Mapper::compact_now() {
  return start_compaction(false);
}

bool Mapper::start_compaction(bool due_only) {
  if (worker_.busy() || !queued_.empty() || rerender_waiting_) return false;
  const CompactionOptions& o = options_.compaction;
  if (due_only && o.retention_days <= 0.0 && o.max_mb <= 0.0) return false;
  auto used = store_->used_bytes();
  if (!used) {
    bump(metrics_.store_errors);
    log_.warn("store", "cannot measure the store: {}", used.message());
    return false;
  }
  const auto plan = plan_compaction(index_, newest_stamp_ns_, *used, last_full_redraw_ns_, o);
  if (!plan) return false;
  // The worker writes through its own connection: nothing may be pending in this one's batch.
  Status ready = store_->flush();
  if (ready)
    ready = worker_.start_compaction(grid_->config(), options_.store, corrections_, plan->through_row);
  if (!ready) {
    bump(metrics_.store_errors);
    spdlog::error("cannot compact the store: {}", ready.message());
    return false;
  }
  ticket_ = RebuildTicket{RebuildCause::Compaction, 0, grid_->config(),
                          "compaction of rows up to " + std::to_string(plan->through_row) + " (" + plan->why +
                              ", " + std::to_string(plan->groups) + " keyframes whole)",
                          std::nullopt};
  return true;
}

void Mapper::finish_compaction(RebuildOutcome outcome) {
  const RebuildTicket ticket = std::move(*ticket_);
  ticket_.reset();
  if (!outcome.compaction || !*outcome.compaction) {
    bump(metrics_.store_errors);
    spdlog::error("{} failed, the store is unchanged: {}", ticket.done,
                  outcome.compaction ? outcome.compaction->message() : std::string("no result"));
    store_deferred_as_drawn();
    return;
  }
  const CompactionReport& report = **outcome.compaction;
  index_.drop_through(report.through_row,
                      report.rows_deleted);  // before the rows kept aside join it (their ids come after)
  store_deferred_as_drawn();
  bump(metrics_.compactions);
  bump(metrics_.compacted_observations, report.rows_deleted);
  metrics_.store_observations.fetch_sub(report.rows_deleted);
  spdlog::info("{}: {} observations replaced by a baseline of {} tiles in {} ms", ticket.done,
               report.rows_deleted, report.tiles, outcome.took.count());
}

}  // namespace slam::mapper
