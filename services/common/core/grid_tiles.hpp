#pragma once
// The map stream's tile codec (GridTiles in map.idl), shared by the mapper that writes it and every
// reader that applies it. A grid of one octet per cell, row-major, is cut into side x side tiles
// numbered row-major (tiles at the right and top edges are clipped to the grid). A patch lists the
// changed tiles in ascending order and carries their cells, each tile row-major, concatenated;
// raw, run-length coded (pairs of <run length - 1, cell octet>), or run-length coded after each
// cell was XORed with the cell every reader holds (the state of the patch's version - 1), whichever
// is shortest. Few cells of a changed tile change within one patch period, so the XORed tiles are
// mostly zero runs: a fifth of the run-length size on a busy fleet map.
// Plain C++: no DDS, no allocation in encode/apply beyond the caller's reused buffers.
#include <cstdint>
#include <span>
#include <vector>

#include "common/core/geometry.hpp"
#include "common/core/result.hpp"

namespace slam {

inline constexpr int32_t kGridTileSide = 32;
// A reader refuses larger tiles (a corrupt side would make one tile the size of the grid's memory).
inline constexpr int32_t kMaxGridTileSide = 1024;

enum class TileEncoding : uint8_t { Raw = 0, RunLength = 1, XorRunLength = 2 };

// How a width x height grid is cut into tiles.
struct TileLayout {
  int32_t width = 0;
  int32_t height = 0;
  int32_t side = kGridTileSide;

  int32_t tiles_x() const { return (width + side - 1) / side; }
  int32_t tiles_y() const { return (height + side - 1) / side; }
  uint32_t count() const { return static_cast<uint32_t>(tiles_x()) * static_cast<uint32_t>(tiles_y()); }
  uint32_t tile_of(int32_t x, int32_t y) const {
    return static_cast<uint32_t>(y / side) * static_cast<uint32_t>(tiles_x()) +
           static_cast<uint32_t>(x / side);
  }
  // The tile's cells, clipped to the grid.
  CellBox box(uint32_t tile) const;
};

// Tiles with changed cells since the last clear: one bit per tile. reset() allocates (on a new
// layout); mark() and clear() do not.
class DirtyTiles {
 public:
  // Every tile clean.
  void reset(const TileLayout& layout);
  void mark(int32_t x, int32_t y) {
    const uint32_t t = layout_.tile_of(x, y);
    bits_[t / 64] |= uint64_t{1} << (t % 64);
  }
  void mark_all();
  void clear();
  bool any() const;
  bool marked(uint32_t tile) const { return (bits_[tile / 64] >> (tile % 64)) & 1u; }
  const TileLayout& layout() const { return layout_; }
  // Calls f(tile) for every marked tile in ascending order.
  template <class F>
  void for_each(F&& f) const {
    for (size_t w = 0; w < bits_.size(); ++w)
      for (uint64_t word = bits_[w]; word != 0; word &= word - 1)
        f(static_cast<uint32_t>(w * 64 + static_cast<size_t>(__builtin_ctzll(word))));
  }

 private:
  TileLayout layout_;
  std::vector<uint64_t> bits_;
};

// One patch's tile part as the IDL carries it.
struct TilePatchView {
  uint32_t side = kGridTileSide;
  uint8_t encoding = static_cast<uint8_t>(TileEncoding::Raw);
  std::span<const uint32_t> tiles;
  std::span<const uint8_t> data;
};

// Reused output buffers of encode_tiles.
struct EncodedTiles {
  TileEncoding encoding = TileEncoding::Raw;
  std::vector<uint32_t> tiles;
  std::vector<uint8_t> data;
  std::vector<uint8_t> raw;       // scratch: the raw cells, kept when run-length coding is not shorter
  std::vector<uint8_t> xored;     // scratch: the cells XOR the readers' cells
  std::vector<uint8_t> xor_data;  // scratch: `xored` run-length coded
  // The whole grid as every reader holds it: the last snapshot with the patches since. Empty (no
  // XOR coding) until readers_hold() is called; kept in step by encode_tiles.
  std::vector<uint8_t> readers_cells;
  // Cells the patch carries (raw size).
  size_t cells() const { return raw.size(); }
};

// Encodes the marked tiles of `cells` (layout dirty.layout(), row-major) in the shortest encoding,
// and records them in out.readers_cells. Buffers keep their capacity.
void encode_tiles(std::span<const uint8_t> cells, const DirtyTiles& dirty, EncodedTiles& out);

// A snapshot of `cells` went out: every reader that follows the stream now holds exactly these.
void readers_hold(std::span<const uint8_t> cells, EncodedTiles& out);

// Applies a patch to `cells` (layout width x height, row-major): checks everything first, so on an
// error nothing is written. The changed tiles' boxes are appended to `changed` when given. An XOR
// coded patch is only right on the cells of the version before it, which the stream's version rule
// (apply version v only on v - 1) already guarantees.
Status apply_tiles(const TilePatchView& patch, std::span<uint8_t> cells, int32_t width, int32_t height,
                   std::vector<CellBox>* changed = nullptr);

}  // namespace slam
