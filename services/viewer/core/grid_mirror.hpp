#pragma once
// The viewer's copy of the mapper's grid: snapshots replace it, tile patches update it in order
// (same layout, version == last + 1), and the box around the changed tiles is remembered so the GPU texture
// is updated with that box only. The box of known cells is kept too, so the view can fit the part of the grid
// that has been mapped rather than its whole (mostly unknown) extent.
#include <cstdint>
#include <optional>
#include <vector>

#include "common/core/result.hpp"
#include "viewer/core/intake_types.hpp"

namespace slam::viewer {

enum class PatchResult {
  Applied,
  Stale,        // already included in the snapshot (version <= current)
  Gap,          // a version was missed: wait for the next snapshot
  WrongLayout,  // the grid was re-laid out: wait for the next snapshot
  NoGrid,       // no snapshot yet
  Invalid       // tiles outside the grid or data that does not match them (nothing applied)
};

class GridMirror {
 public:
  Status apply_snapshot(msg::GridSnapshot&& snapshot);
  PatchResult apply_patch(const msg::GridTiles& patch);

  bool has_grid() const { return has_grid_; }
  const msg::GridInfo& info() const { return info_; }
  const std::vector<uint8_t>& cells() const { return cells_; }
  uint32_t layout_id() const { return layout_id_; }
  uint64_t version() const { return version_; }
  bool waiting_for_snapshot() const { return waiting_; }
  WorldBox bounds() const;
  // Map-frame box around every free or occupied cell; nothing while the whole grid is unknown.
  // Patches only widen it (a cell that turns unknown again is rare); a snapshot recomputes it.
  std::optional<WorldBox> known_bounds() const;

  // The cell octet at a map-frame point; nothing when outside the grid.
  std::optional<uint8_t> cell_at(Vec2 world) const;

  // Cells changed since the last call (the whole grid after a snapshot), then forgets them.
  CellBox take_dirty();
  // True once after a snapshot changed size or layout (the texture must be re-created).
  bool take_layout_changed();

 private:
  bool has_grid_ = false;
  bool waiting_ = false;
  bool layout_changed_ = false;
  uint32_t layout_id_ = 0;
  uint64_t version_ = 0;
  msg::GridInfo info_;
  GridGeometry geometry_;  // info_ as the common grid geometry
  std::vector<uint8_t> cells_;
  CellBox dirty_;
  CellBox known_;
  std::vector<CellBox> changed_;  // the patch being applied, reused

  void include_known(const CellBox& area);
};

}  // namespace slam::viewer
