// Rebuild: replays the store into a new grid. Rows stream from SQLite into reused buffers, so the
// only memory that grows is the grid itself.
#include "mapper/rebuild.hpp"

namespace slam::mapper {

Result<OccupancyGrid> rebuild_grid(const GridConfig& config, ObservationStore& store, RebuildStats* stats) {
  RebuildStats local;
  RebuildStats& st = stats ? *stats : local;
  st = RebuildStats{};
  auto grid = OccupancyGrid::create(config);
  if (!grid) return Error{grid.message()};

  auto prior = store.load_prior();
  if (!prior) return Error{prior.message()};
  if (prior->has_value()) {
    auto cells = grid->apply_prior(**prior);
    if (cells) st.prior_cells = *cells;
    else if (st.first_error.empty()) st.first_error = cells.message();
  }

  const Status read = store.for_each([&](const ObservationRecord& rec) {
    auto r = grid->integrate(rec.obs);
    if (!r) {
      ++st.rejected;
      if (st.first_error.empty()) st.first_error = "observation " + std::to_string(rec.id) + ": " + r.message();
      return;
    }
    ++st.observations;
    st.clipped += r->clipped;
  });
  if (!read) return Error{read.message()};

  auto obstructions = store.obstructions();
  if (!obstructions) return Error{obstructions.message()};
  for (const Point2d& p : *obstructions) {
    if (Status s = grid->obstruct(p.x, p.y); !s) {
      if (st.first_error.empty()) st.first_error = s.message();
      continue;
    }
    ++st.obstructions;
  }
  return std::move(*grid);
}

}  // namespace slam::mapper
