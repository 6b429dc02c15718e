// Rebuild: replays the store into a new grid. Rows stream from SQLite into a few reused batches,
// so the only memory that grows is the grid itself.
#include "mapper/core/rebuild.hpp"

#include <limits>
#include <thread>
#include <vector>

#include "mapper/core/observation_batches.hpp"

namespace slam::mapper {
namespace {

// Enough per batch that the hand-off costs nothing next to the ray casting; three batches let the
// reader fill one while the integrator works through another.
constexpr size_t kBatchObservations = 2048;
constexpr size_t kBatchesInFlight = 3;

}  // namespace

Status apply_stored_start(OccupancyGrid& grid, ObservationStore& store, RebuildStats& st) {
  auto baseline = store.load_baseline();
  if (!baseline) return baseline.error();
  if (baseline->has_value()) st.baseline_cells = grid.apply_baseline(**baseline);
  if (baseline->has_value() && !(*baseline)->prior_pending) return Status::ok();  // it holds the prior
  auto prior = store.load_prior();
  if (!prior) return prior.error();
  if (prior->has_value()) {
    auto cells = grid.apply_prior(**prior);
    if (cells)
      st.prior_cells = *cells;
    else if (st.first_error.empty())
      st.first_error = cells.message();
  }
  return Status::ok();
}

namespace {

// The start, then the rows up to `through_row` in insertion order, each moved by its correction.
Result<OccupancyGrid> replay(const GridConfig& config, ObservationStore& store, RebuildStats& st,
                             const KeyframeCorrections& corrections, FootprintIndex* index,
                             int64_t through_row) {
  st = RebuildStats{};
  auto grid = OccupancyGrid::create(config);
  if (!grid) return grid.error();
  if (index) index->clear();
  SLAM_TRY(apply_stored_start(*grid, store, st));

  // SQLite reads, decodes and corrects on a second thread while this one ray-casts: together they
  // take about as long as the ray casting alone (docs/performance.md, mapper rebuild).
  ObservationBatches batches(kBatchesInFlight);
  Status read = Status::ok();
  std::thread reader([&] {
    ObservationBatch* batch = batches.take_empty();
    std::vector<Vec2> hits;
    std::vector<Vec2> misses;
    read = store.for_each(
        [&](const ObservationRecord& rec) {
          const Pose& correction = corrections.lookup(rec.keyframe_id);
          if (is_identity(correction))
            batch->add(rec.id, rec.obs, rec.keyframe_id, rec.stamp_ns);
          else
            batch->add(rec.id, to_map_frame(correction, rec.obs, hits, misses), rec.keyframe_id,
                       rec.stamp_ns);
          if (batch->entries.size() < kBatchObservations) return;
          batches.push_full(batch);
          batch = batches.take_empty();
        },
        through_row);
    if (!batch->entries.empty()) batches.push_full(batch);
    batches.finish();
  });
  while (ObservationBatch* batch = batches.pop_full()) {
    batch->for_each_entry([&](const ObservationBatch::Entry& e, const ObservationView& obs) {
      auto r = grid->integrate(obs);
      if (!r) {
        ++st.rejected;
        if (st.first_error.empty())
          st.first_error = "observation " + std::to_string(e.id) + ": " + r.message();
        return;
      }
      ++st.observations;
      st.clipped += r->clipped;
      if (index) index->add(e.keyframe, e.id, corrections.lookup(e.keyframe), box_of(obs), e.stamp_ns);
    });
    batches.give_back(batch);
  }
  reader.join();
  if (!read) return read.error();
  return std::move(*grid);
}

}  // namespace

Result<OccupancyGrid> rebuild_through(const GridConfig& config, ObservationStore& store, int64_t through_row,
                                      const KeyframeCorrections& corrections, RebuildStats* stats) {
  RebuildStats local;
  return replay(config, store, stats ? *stats : local, corrections, nullptr, through_row);
}

Result<OccupancyGrid> rebuild_grid(const GridConfig& config, ObservationStore& store, RebuildStats* stats,
                                   const KeyframeCorrections& corrections, FootprintIndex* index) {
  RebuildStats local;
  RebuildStats& st = stats ? *stats : local;
  auto grid = replay(config, store, st, corrections, index, std::numeric_limits<int64_t>::max());
  if (!grid) return grid.error();

  auto obstructions = store.obstructions();
  if (!obstructions) return obstructions.error();
  for (const Vec2& p : *obstructions) {
    if (Status s = grid->obstruct(p.x, p.y); !s) {
      if (st.first_error.empty()) st.first_error = s.message();
      continue;
    }
    ++st.obstructions;
  }
  return std::move(*grid);
}

}  // namespace slam::mapper
