// Probe placement, payloads and detection in the map stream for bench_pipeline.
#include "pipeline_probe.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "common/core/clock.hpp"
#include "common/core/grid_tiles.hpp"
#include "protocol/v1_codec.hpp"

namespace slam::bench {
namespace {

constexpr uint32_t kFirstColumn = 20;  // cells from the grid's left edge
constexpr uint32_t kColumnStep = 7;
constexpr uint32_t kFirstRow = 30;  // obstacle rows from the grid's bottom edge
constexpr uint32_t kRowStep = 15;
constexpr uint32_t kBands = 4;      // rows 30, 45, 60, 75: below the world's wall at row 100
constexpr uint32_t kRayCells = 10;  // the probe robot stands this many cells below its point
constexpr double kUnitsPerMetre = 100.0;
constexpr double kIntoCellCm = 2.0;  // 2 cm into a 5 cm cell: no rounding puts it in a neighbour

uint32_t columns_per_band(const GridLayout& g) {
  const auto side = static_cast<uint32_t>(std::lround(g.side_m / g.resolution));
  return side > 2 * kFirstColumn ? (side - 2 * kFirstColumn) / kColumnStep : 0;
}

// Centimetre coordinate of a point kIntoCellCm inside cell `index` along an axis starting at origin.
double cell_point_m(double origin, double resolution, uint32_t index) {
  return (std::round((origin + index * resolution) * kUnitsPerMetre) + kIntoCellCm) / kUnitsPerMetre;
}

}  // namespace

size_t ProbeSet::capacity(const GridLayout& grid) {
  return static_cast<size_t>(columns_per_band(grid)) * kBands;
}

ProbeSet::ProbeSet(const GridLayout& grid, size_t count) : grid_(grid) {
  const uint32_t per_band = columns_per_band(grid);
  probes_.resize(std::min(count, capacity(grid)));
  for (size_t k = 0; k < probes_.size(); ++k) {
    Probe& p = probes_[k];
    const uint32_t column = kFirstColumn + kColumnStep * static_cast<uint32_t>(k % per_band);
    const uint32_t row = kFirstRow + kRowStep * static_cast<uint32_t>(k / per_band);
    p.x = cell_point_m(grid.origin_x, grid.resolution, column);
    p.y = cell_point_m(grid.origin_y, grid.resolution, row);
    const protocol::Point robot{p.x, cell_point_m(grid.origin_y, grid.resolution, row - kRayCells)};
    const protocol::Point obstacle{p.x, p.y};
    if (!protocol::encode_v1_adv(robot, {&obstacle, 1}, kUnitsPerMetre, p.payload)) std::abort();
  }
}

void ProbeSet::mark_sent(size_t k, int64_t monotonic_ns) {
  std::lock_guard lock(mutex_);
  probes_[k].sent_ns = monotonic_ns;
}

void ProbeSet::on_snapshot(const GridSnapshot& s) {
  const int64_t now = monotonic_ns();
  std::lock_guard lock(mutex_);
  layout_ = Layout{s.layout_id(),         s.info().width(),      s.info().height(),
                   s.info().origin().x(), s.info().origin().y(), s.info().resolution()};
  cells_ = s.cells();
  if (cells_.size() == static_cast<size_t>(s.info().width()) * s.info().height())
    check_box({0, 0, static_cast<int32_t>(s.info().width()), static_cast<int32_t>(s.info().height())}, now);
}

void ProbeSet::on_patch(const GridTiles& p) {
  const int64_t now = monotonic_ns();
  patches_.fetch_add(1);
  patch_bytes_.fetch_add(GridTiles::getCdrSerializedSize(p));
  std::lock_guard lock(mutex_);
  if (!layout_ || p.layout_id() != layout_->id) return;  // from before the snapshot we know
  changed_.clear();
  const TilePatchView view{p.tile_side(), p.encoding(), p.tiles(), p.data()};
  if (!apply_tiles(view, cells_, static_cast<int32_t>(layout_->width), static_cast<int32_t>(layout_->height),
                   &changed_))
    return;
  for (const CellBox& box : changed_) {
    patch_cells_.fetch_add(box.cells());
    check_box(box, now);
  }
}

void ProbeSet::check_box(const CellBox& box, int64_t now) {
  for (Probe& p : probes_) {
    if (p.sent_ns == 0 || p.delay_ns >= 0) continue;
    const double fx = std::floor((p.x - layout_->origin_x) / layout_->resolution);
    const double fy = std::floor((p.y - layout_->origin_y) / layout_->resolution);
    if (fx < box.x0 || fy < box.y0 || fx >= static_cast<double>(box.x0) + box.width ||
        fy >= static_cast<double>(box.y0) + box.height)
      continue;
    const size_t i = static_cast<size_t>(fy) * layout_->width + static_cast<size_t>(fx);
    if ((cells_[i] & CELL_STATE_MASK) == CELL_OCCUPIED) p.delay_ns = now - p.sent_ns;
  }
}

ProbeSet::Summary ProbeSet::summary(int64_t now_monotonic_ns) const {
  std::lock_guard lock(mutex_);
  Summary out;
  std::vector<int64_t> delays;
  for (const Probe& p : probes_) {
    if (p.sent_ns == 0) continue;
    ++out.sent;
    if (p.delay_ns >= 0) ++out.seen;
    delays.push_back(p.delay_ns >= 0 ? p.delay_ns : now_monotonic_ns - p.sent_ns);
  }
  if (delays.empty()) return out;
  std::sort(delays.begin(), delays.end());
  auto at = [&](double q) {
    const auto k = std::min(delays.size() - 1,
                            static_cast<size_t>(std::ceil(q * static_cast<double>(delays.size()))) - 1);
    return static_cast<double>(delays[k]) / 1e6;
  };
  out.p50_ms = at(0.50);
  out.p99_ms = at(0.99);
  out.max_ms = static_cast<double>(delays.back()) / 1e6;
  return out;
}

}  // namespace slam::bench
