#pragma once
// The bridge's copy of the mapper's grid, kept from the snapshot and the tile patches in between
// (common/core/grid_tiles), and the region changed since a face last took it: a face sends the
// whole grid now and then and only that region between.
#include <cstdint>
#include <span>
#include <vector>

#include "common/core/fleet_messages.hpp"
#include "common/core/geometry.hpp"
#include "common/core/result.hpp"

namespace slam::bridge {

class MapView {
 public:
  // A snapshot replaces the grid (and makes the whole grid the changed region).
  Status ingest(msg::GridSnapshot&& s);
  // A patch that follows the grid's version on its layout is applied; any other is skipped (the
  // next snapshot catches up). Skipped and refused patches are an error, nothing changed.
  Status ingest(const msg::GridTiles& t);

  bool has_grid() const { return has_grid_; }
  const GridGeometry& geometry() const { return geometry_; }
  std::span<const uint8_t> cells() const { return cells_; }
  int64_t stamp_ns() const { return stamp_ns_; }
  // Bumped by every snapshot and applied patch.
  uint64_t revision() const { return revision_; }

  // The box of every cell changed since the last take_changed() (empty when nothing changed).
  const CellBox& changed() const { return changed_; }
  // That box; clears it.
  CellBox take_changed();

 private:
  bool has_grid_ = false;
  uint32_t layout_id_ = 0;
  uint64_t version_ = 0;
  int64_t stamp_ns_ = 0;
  uint64_t revision_ = 0;
  GridGeometry geometry_;
  std::vector<uint8_t> cells_;
  CellBox changed_;
  std::vector<CellBox> scratch_;
};

}  // namespace slam::bridge
