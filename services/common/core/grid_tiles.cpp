// The map stream's tile codec (see grid_tiles.hpp).
#include "common/core/grid_tiles.hpp"

#include <algorithm>
#include <string>

namespace slam {
namespace {

constexpr size_t kMaxRun = 256;  // a run length is stored as one octet, minus one

// Appends the tile's cells, row-major, to `out`.
void append_tile(std::span<const uint8_t> cells, const TileLayout& layout, uint32_t tile,
                 std::vector<uint8_t>& out) {
  const CellBox box = layout.box(tile);
  for (int32_t y = box.y0; y < box.y0 + box.height; ++y) {
    const auto row = cells.begin() +
                     static_cast<std::ptrdiff_t>(static_cast<size_t>(y) * static_cast<size_t>(layout.width) +
                                                 static_cast<size_t>(box.x0));
    out.insert(out.end(), row, row + box.width);
  }
}

// Copies the tile's cells from `from` into the same place of `to` (both of the layout's size).
void copy_tile(std::span<const uint8_t> from, const TileLayout& layout, uint32_t tile,
               std::span<uint8_t> to) {
  const CellBox box = layout.box(tile);
  for (int32_t y = box.y0; y < box.y0 + box.height; ++y) {
    const size_t at =
        static_cast<size_t>(y) * static_cast<size_t>(layout.width) + static_cast<size_t>(box.x0);
    std::copy_n(from.begin() + static_cast<std::ptrdiff_t>(at), box.width,
                to.begin() + static_cast<std::ptrdiff_t>(at));
  }
}

// Run-length codes `raw` into `out`; false (out partly written) as soon as it is not shorter.
bool run_length(std::span<const uint8_t> raw, std::vector<uint8_t>& out) {
  out.clear();
  size_t i = 0;
  while (i < raw.size()) {
    const uint8_t value = raw[i];
    size_t run = 1;
    while (run < kMaxRun && i + run < raw.size() && raw[i + run] == value) ++run;
    if (out.size() + 2 >= raw.size()) return false;
    out.push_back(static_cast<uint8_t>(run - 1));
    out.push_back(value);
    i += run;
  }
  return true;
}

}  // namespace

CellBox TileLayout::box(uint32_t tile) const {
  const auto tx = static_cast<int32_t>(tile % static_cast<uint32_t>(tiles_x()));
  const auto ty = static_cast<int32_t>(tile / static_cast<uint32_t>(tiles_x()));
  const int32_t x0 = tx * side;
  const int32_t y0 = ty * side;
  return {x0, y0, std::min(side, width - x0), std::min(side, height - y0)};
}

void DirtyTiles::reset(const TileLayout& layout) {
  layout_ = layout;
  bits_.assign((size_t{layout.count()} + 63) / 64, 0);
}

void DirtyTiles::mark_all() {
  std::fill(bits_.begin(), bits_.end(), ~uint64_t{0});
  const uint32_t tail = layout_.count() % 64;
  if (tail != 0 && !bits_.empty()) bits_.back() = (uint64_t{1} << tail) - 1;
}

void DirtyTiles::clear() {
  std::fill(bits_.begin(), bits_.end(), 0);
}

bool DirtyTiles::any() const {
  return std::any_of(bits_.begin(), bits_.end(), [](uint64_t w) { return w != 0; });
}

void encode_tiles(std::span<const uint8_t> cells, const DirtyTiles& dirty, EncodedTiles& out) {
  out.tiles.clear();
  out.raw.clear();
  out.xored.clear();
  const bool with_xor = out.readers_cells.size() == cells.size();
  dirty.for_each([&](uint32_t tile) {
    out.tiles.push_back(tile);
    const size_t from = out.raw.size();
    append_tile(cells, dirty.layout(), tile, out.raw);
    if (!with_xor) return;
    append_tile(out.readers_cells, dirty.layout(), tile, out.xored);
    for (size_t i = from; i < out.raw.size(); ++i) out.xored[i] ^= out.raw[i];
    copy_tile(cells, dirty.layout(), tile, out.readers_cells);
  });
  const bool rle = run_length(out.raw, out.data);
  const bool xor_rle = with_xor && run_length(out.xored, out.xor_data);
  if (xor_rle && (!rle || out.xor_data.size() < out.data.size())) {
    out.encoding = TileEncoding::XorRunLength;
    out.data.swap(out.xor_data);
  } else if (rle) {
    out.encoding = TileEncoding::RunLength;
  } else {
    out.encoding = TileEncoding::Raw;
    out.data.assign(out.raw.begin(), out.raw.end());
  }
}

void readers_hold(std::span<const uint8_t> cells, EncodedTiles& out) {
  out.readers_cells.assign(cells.begin(), cells.end());
}

Status apply_tiles(const TilePatchView& patch, std::span<uint8_t> cells, int32_t width, int32_t height,
                   std::vector<CellBox>* changed) {
  if (width <= 0 || height <= 0 || cells.size() != static_cast<size_t>(width) * static_cast<size_t>(height))
    return Error{"tile patch: the grid is empty or its cells do not match its size"};
  if (patch.side == 0 || patch.side > static_cast<uint32_t>(kMaxGridTileSide))
    return Error{"tile patch: tile side " + std::to_string(patch.side) + " is outside 1.." +
                 std::to_string(kMaxGridTileSide)};
  if (patch.encoding > static_cast<uint8_t>(TileEncoding::XorRunLength))
    return Error{"tile patch: unknown encoding " + std::to_string(patch.encoding)};
  const TileLayout layout{width, height, static_cast<int32_t>(patch.side)};
  const uint32_t count = layout.count();

  // Every check before the first write: a bad patch leaves the grid as it was.
  uint64_t total = 0;
  for (size_t i = 0; i < patch.tiles.size(); ++i) {
    const uint32_t tile = patch.tiles[i];
    if (tile >= count)
      return Error{"tile patch: tile " + std::to_string(tile) + " is outside the grid's " +
                   std::to_string(count) + " tiles"};
    if (i > 0 && tile <= patch.tiles[i - 1])
      return Error{"tile patch: tiles are not in ascending order at " + std::to_string(i)};
    total += layout.box(tile).cells();
  }
  const bool raw = patch.encoding == static_cast<uint8_t>(TileEncoding::Raw);
  if (raw) {
    if (patch.data.size() != total)
      return Error{"tile patch: " + std::to_string(patch.data.size()) + " octets of cells, the tiles hold " +
                   std::to_string(total)};
  } else {
    if (patch.data.size() % 2 != 0) return Error{"tile patch: run-length data has an odd length"};
    uint64_t runs = 0;
    for (size_t i = 0; i < patch.data.size(); i += 2) runs += size_t{patch.data[i]} + 1;
    if (runs != total)
      return Error{"tile patch: runs cover " + std::to_string(runs) + " cells, the tiles hold " +
                   std::to_string(total)};
  }

  // Walks the run-length data (or the raw cells) as one stream over the tiles' rows.
  const bool xored = patch.encoding == static_cast<uint8_t>(TileEncoding::XorRunLength);
  size_t pos = 0;       // in patch.data
  size_t run_left = 0;  // cells left in the current run
  const auto fill = [&](uint8_t* dst, size_t n) {
    if (raw) {
      std::copy_n(patch.data.begin() + static_cast<std::ptrdiff_t>(pos), n, dst);
      pos += n;
      return;
    }
    while (n > 0) {
      if (run_left == 0) {
        run_left = size_t{patch.data[pos]} + 1;
        pos += 2;
      }
      const size_t k = std::min(n, run_left);
      const uint8_t value = patch.data[pos - 1];
      if (!xored)
        std::fill_n(dst, k, value);
      else if (value != 0)
        for (size_t i = 0; i < k; ++i) dst[i] ^= value;
      dst += k;
      n -= k;
      run_left -= k;
    }
  };
  for (const uint32_t tile : patch.tiles) {
    const CellBox box = layout.box(tile);
    for (int32_t y = box.y0; y < box.y0 + box.height; ++y)
      fill(cells.data() + static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(box.x0),
           static_cast<size_t>(box.width));
    if (changed) changed->push_back(box);
  }
  return Status::ok();
}

}  // namespace slam
