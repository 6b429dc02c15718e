// Partial re-render: the plan on the loop, the drawing on the worker (see partial_rerender.hpp).
#include "mapper/core/partial_rerender.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace slam::mapper {
namespace {

// The tiles a map-frame box covers, with a cell of margin against rounding, clipped to the grid.
struct TileRange {
  int32_t x0 = 0, y0 = 0, x1 = -1, y1 = -1;  // inclusive; empty when x1 < x0
  bool empty() const { return x1 < x0 || y1 < y0; }
};

TileRange tiles_of(const MapBox& box, const GridGeometry& g) {
  if (box.empty()) return {};
  const Vec2 lo = g.to_grid({box.x0, box.y0});
  const Vec2 hi = g.to_grid({box.x1, box.y1});
  const double x0 = std::max(std::floor(lo.x) - 1, 0.0), y0 = std::max(std::floor(lo.y) - 1, 0.0);
  const double x1 = std::min<double>(std::floor(hi.x) + 1, g.width - 1);
  const double y1 = std::min<double>(std::floor(hi.y) + 1, g.height - 1);
  if (!(x0 <= x1 && y0 <= y1)) return {};
  return {static_cast<int32_t>(x0) / kGridTileSide, static_cast<int32_t>(y0) / kGridTileSide,
          static_cast<int32_t>(x1) / kGridTileSide, static_cast<int32_t>(y1) / kGridTileSide};
}

bool inside(const MapBox& box, const GridGeometry& g) {
  const Vec2 lo = g.to_grid({box.x0, box.y0});
  const Vec2 hi = g.to_grid({box.x1, box.y1});
  return lo.x >= 0.0 && lo.y >= 0.0 && hi.x < g.width && hi.y < g.height;
}

// The box `box` moved by `delta` (its corners' box: it holds every moved point), and how far its
// farthest point moved.
std::pair<MapBox, double> moved_box(const MapBox& box, const Pose& delta) {
  MapBox out;
  double shift = 0.0;
  for (const Vec2 c :
       {Vec2{box.x0, box.y0}, Vec2{box.x1, box.y0}, Vec2{box.x0, box.y1}, Vec2{box.x1, box.y1}}) {
    const Vec2 m = delta.transform(c);
    out.add(m);
    shift = std::max(shift, std::hypot(m.x - c.x, m.y - c.y));
  }
  return {out, shift};
}

RerenderDecision full(std::string reason) {
  RerenderDecision d;
  d.kind = RerenderDecision::Kind::Full;
  d.reason = std::move(reason);
  return d;
}

}  // namespace

Status validate(const RerenderOptions& o) {
  if (!(o.min_shift_cells >= 0.0) || !std::isfinite(o.min_shift_cells))
    return Error{"rerender.min_shift_cells: must be >= 0, got " + std::to_string(o.min_shift_cells)};
  if (!(o.max_tile_fraction >= 0.0 && o.max_tile_fraction <= 1.0))
    return Error{"rerender.max_tile_fraction: must be in [0, 1], got " + std::to_string(o.max_tile_fraction)};
  return Status::ok();
}

RerenderDecision plan_rerender(const FootprintIndex& index, const KeyframeCorrections& corrections,
                               const OccupancyGrid& grid, const RerenderOptions& options) {
  RerenderDecision decision;
  RerenderPlan& plan = decision.plan;
  plan.geometry = grid.geometry();
  plan.config = grid.config();
  plan.layout_version = grid.layout_version();
  const GridGeometry& g = plan.geometry;
  const TileLayout layout{g.width, g.height, kGridTileSide};
  const double min_shift = options.min_shift_cells * g.resolution;
  const std::span<const FootprintGroup> groups = index.groups();

  // Moved keyframes: their old and new tiles are redrawn. `drawn_box` is where each group will be drawn.
  std::vector<MapBox> drawn_box(groups.size());
  std::vector<uint8_t> moved(groups.size(), 0);
  DirtyTiles redraw;
  redraw.reset(layout);
  TileRange bounds{layout.tiles_x(), layout.tiles_y(), -1, -1};
  const auto mark = [&](const MapBox& box) {
    const TileRange r = tiles_of(box, g);
    if (r.empty()) return;
    for (int32_t ty = r.y0; ty <= r.y1; ++ty)
      for (int32_t tx = r.x0; tx <= r.x1; ++tx) redraw.mark(tx * kGridTileSide, ty * kGridTileSide);
    bounds = {std::min(bounds.x0, r.x0), std::min(bounds.y0, r.y0), std::max(bounds.x1, r.x1),
              std::max(bounds.y1, r.y1)};
  };
  for (size_t i = 0; i < groups.size(); ++i) {
    const FootprintGroup& grp = groups[i];
    drawn_box[i] = grp.box;
    if (!is_finite(grp.drawn))
      return full("keyframe " + std::to_string(grp.keyframe) + " is drawn with several corrections");
    if (grp.keyframe == 0) continue;  // never moves
    const Pose& wanted = corrections.lookup(grp.keyframe);
    if (wanted == grp.drawn) continue;
    const auto [box, shift] = moved_box(grp.box, wanted.compose(grp.drawn.inverse()));
    if (!(shift > min_shift)) continue;
    if (!inside(box, g))
      return full("keyframe " + std::to_string(grp.keyframe) + " moves its observations beyond the grid");
    moved[i] = 1;
    drawn_box[i] = box;
    ++plan.moved;
    mark(grp.box);
    mark(box);
  }
  if (plan.moved == 0) return decision;  // Nothing
  redraw.for_each([&](uint32_t tile) { plan.tiles.push_back(tile); });
  if (static_cast<double>(plan.tiles.size()) > options.max_tile_fraction * layout.count())
    return full(std::to_string(plan.tiles.size()) + " of " + std::to_string(layout.count()) +
                " tiles to redraw");

  // Every group drawn into a redrawn tile is replayed (moved ones at their new correction).
  for (size_t i = 0; i < groups.size(); ++i) {
    const TileRange r = tiles_of(drawn_box[i], g);
    const int32_t x0 = std::max(r.x0, bounds.x0), x1 = std::min(r.x1, bounds.x1);
    const int32_t y0 = std::max(r.y0, bounds.y0), y1 = std::min(r.y1, bounds.y1);
    bool touches = false;
    for (int32_t ty = y0; ty <= y1 && !touches; ++ty)
      for (int32_t tx = x0; tx <= x1 && !touches; ++tx)
        touches = redraw.marked(static_cast<uint32_t>(ty) * static_cast<uint32_t>(layout.tiles_x()) +
                                static_cast<uint32_t>(tx));
    if (!touches) continue;
    const FootprintGroup& grp = groups[i];
    plan.replays.push_back(RerenderPlan::Replay{grp.keyframe, grp.first_row, grp.last_row,
                                                moved[i] ? corrections.lookup(grp.keyframe) : grp.drawn,
                                                static_cast<uint32_t>(i), moved[i] != 0});
  }
  decision.kind = RerenderDecision::Kind::Partial;
  return decision;
}

namespace {

// render_tiles' reads and drawing, in one read transaction.
Status draw_tiles(const RerenderPlan& plan, ObservationStore& store, TileRender& out) {
  out.canvas.reset(plan.geometry, plan.config, plan.tiles);
  // The start a full rebuild has (rebuild.cpp apply_stored_start): the baseline's tiles under these,
  // then the prior unless the baseline holds it.
  const MapBox region = out.canvas.box();
  auto baseline = store.load_baseline(&region);
  if (!baseline) return baseline.status();
  if (baseline->has_value()) out.canvas.apply_baseline(**baseline);
  if (!baseline->has_value() || (*baseline)->prior_pending) {
    auto prior = store.load_prior();
    if (!prior) return prior.status();
    if (prior->has_value()) out.canvas.apply_prior(**prior);
  }

  // The replayed groups' rows, in insertion order.
  std::vector<std::pair<int64_t, uint32_t>> rows;  // row, replay
  for (size_t i = 0; i < plan.replays.size(); ++i) {
    const RerenderPlan::Replay& r = plan.replays[i];
    SLAM_TRY(store.rows_of(r.keyframe, r.first_row, r.last_row,
                           [&](int64_t row) { rows.emplace_back(row, static_cast<uint32_t>(i)); }));
  }
  std::sort(rows.begin(), rows.end());
  std::vector<int64_t> ids(rows.size());
  for (size_t i = 0; i < rows.size(); ++i) ids[i] = rows[i].first;

  out.boxes.resize(plan.replays.size());
  std::vector<Vec2> hits, misses;
  size_t next = 0;
  Status read = store.for_each_row(ids, [&](const ObservationRecord& rec) {
    if (out.outside_grid) return;
    while (next < rows.size() && rows[next].first < rec.id) ++next;
    if (next == rows.size() || rows[next].first != rec.id) return;
    const uint32_t i = rows[next].second;
    const RerenderPlan::Replay& r = plan.replays[i];
    ++out.rows_read;
    const ObservationView view = is_identity(r.pose) ? rec.obs : to_map_frame(r.pose, rec.obs, hits, misses);
    const MapBox box = box_of(view);
    if (!out.canvas.touches(box)) {
      if (r.moved) out.boxes[i].add(box);
      return;
    }
    switch (out.canvas.integrate(view)) {
      case TileCanvas::Drawn::Yes:
        ++out.replayed;
        if (r.moved) out.boxes[i].add(box);
        return;
      case TileCanvas::Drawn::Rejected:
        ++out.rejected;
        return;
      case TileCanvas::Drawn::OutsideGrid:
        out.outside_grid = true;
        return;
    }
  });
  return read;
}

}  // namespace

Result<TileRender> render_tiles(RerenderPlan plan, ObservationStore& store) {
  TileRender out;
  SLAM_TRY(store.read_together([&] { return draw_tiles(plan, store, out); }));
  out.plan = std::move(plan);
  return out;
}

void record_redraw(const TileRender& render, FootprintIndex& index, int64_t stamp_ns) {
  for (size_t i = 0; i < render.plan.replays.size(); ++i) {
    const RerenderPlan::Replay& r = render.plan.replays[i];
    if (r.moved) index.redraw(r.group, r.pose, render.boxes[i], stamp_ns);
  }
}

}  // namespace slam::mapper
