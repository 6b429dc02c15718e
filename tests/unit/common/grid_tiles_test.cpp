// The map stream's tile codec: dirty tiles, encode, apply, and what apply refuses.
#include "common/core/grid_tiles.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

namespace slam {
namespace {

TilePatchView view_of(const EncodedTiles& e, uint32_t side = kGridTileSide) {
  return {side, static_cast<uint8_t>(e.encoding), e.tiles, e.data};
}

// A grid with walls and free space, like the mapper's (long runs, a few distinct octets).
std::vector<uint8_t> room(int32_t w, int32_t h) {
  std::vector<uint8_t> cells(static_cast<size_t>(w) * static_cast<size_t>(h), 0);
  for (int32_t y = 0; y < h; ++y)
    for (int32_t x = 0; x < w; ++x)
      cells[static_cast<size_t>(y * w + x)] = (x % 40 == 0 || y % 40 == 0) ? 6 : (x < w / 2 ? 1 : 0);
  return cells;
}

TEST(TileLayout, ClipsEdgeTilesToTheGrid) {
  const TileLayout layout{70, 33, 32};
  EXPECT_EQ(layout.tiles_x(), 3);
  EXPECT_EQ(layout.tiles_y(), 2);
  EXPECT_EQ(layout.count(), 6u);
  EXPECT_EQ(layout.box(0), (CellBox{0, 0, 32, 32}));
  EXPECT_EQ(layout.box(2), (CellBox{64, 0, 6, 32}));
  EXPECT_EQ(layout.box(5), (CellBox{64, 32, 6, 1}));
  EXPECT_EQ(layout.tile_of(69, 32), 5u);
}

TEST(DirtyTiles, MarksClearsAndListsInOrder) {
  DirtyTiles d;
  d.reset({130, 70, 32});  // 5 x 3 tiles
  EXPECT_FALSE(d.any());
  d.mark(129, 69);
  d.mark(0, 0);
  d.mark(31, 31);  // same tile as (0, 0)
  std::vector<uint32_t> listed;
  d.for_each([&](uint32_t t) { listed.push_back(t); });
  EXPECT_EQ(listed, (std::vector<uint32_t>{0, 14}));
  d.clear();
  EXPECT_FALSE(d.any());
  d.mark_all();
  listed.clear();
  d.for_each([&](uint32_t t) { listed.push_back(t); });
  EXPECT_EQ(listed.size(), 15u) << "mark_all marks only tiles of the grid";
}

// Grids that are not a multiple of the tile side, changes in every edge tile: the mirror equals
// the source cell for cell, whichever encoding was chosen.
TEST(GridTiles, RoundTripsOnGridsNotAMultipleOfTheTileSide) {
  std::mt19937 rng(7);
  for (const auto& [w, h] : {std::pair{70, 33}, std::pair{32, 32}, std::pair{1, 1}, std::pair{97, 5}}) {
    std::vector<uint8_t> source = room(w, h);
    std::vector<uint8_t> mirror = source;
    DirtyTiles dirty;
    dirty.reset({w, h, kGridTileSide});
    for (int k = 0; k < 50; ++k) {  // scattered changes, corners included
      const int32_t x = static_cast<int32_t>(rng() % static_cast<uint32_t>(w));
      const int32_t y = static_cast<int32_t>(rng() % static_cast<uint32_t>(h));
      source[static_cast<size_t>(y * w + x)] = static_cast<uint8_t>(rng() % 16);
      dirty.mark(x, y);
    }
    source.back() = 9;
    dirty.mark(w - 1, h - 1);
    EncodedTiles e;
    encode_tiles(source, dirty, e);
    std::vector<CellBox> changed;
    ASSERT_TRUE(apply_tiles(view_of(e), mirror, w, h, &changed)) << w << "x" << h;
    EXPECT_EQ(mirror, source) << w << "x" << h;
    EXPECT_EQ(changed.size(), e.tiles.size());
    EXPECT_EQ(changed.back(), TileLayout({w, h, kGridTileSide}).box(e.tiles.back()));
  }
}

TEST(GridTiles, RunLengthIsChosenWhenShorterAndRawOtherwise) {
  const int32_t w = 64, h = 64;
  DirtyTiles dirty;
  dirty.reset({w, h, kGridTileSide});
  dirty.mark_all();
  EncodedTiles e;
  const std::vector<uint8_t> flat = room(w, h);
  encode_tiles(flat, dirty, e);
  EXPECT_EQ(e.encoding, TileEncoding::RunLength);
  EXPECT_LT(e.data.size(), e.cells() / 4);
  EXPECT_EQ(e.cells(), flat.size());

  std::vector<uint8_t> noise(flat.size());
  std::mt19937 rng(3);
  for (auto& c : noise) c = static_cast<uint8_t>(rng());
  encode_tiles(noise, dirty, e);
  EXPECT_EQ(e.encoding, TileEncoding::Raw);
  EXPECT_EQ(e.data.size(), noise.size());
  std::vector<uint8_t> mirror(noise.size(), 0);
  ASSERT_TRUE(apply_tiles(view_of(e), mirror, w, h));
  EXPECT_EQ(mirror, noise);
}

// A stream of patches after a snapshot: few cells change per patch, so the XOR coding is chosen and
// much shorter, and a reader that follows the versions stays equal to the source cell for cell.
TEST(GridTiles, XorCodedPatchesKeepAFollowingReaderExactAndAreShorter) {
  const int32_t w = 97, h = 70;
  std::vector<uint8_t> source = room(w, h);
  EncodedTiles e;
  readers_hold(source, e);
  std::vector<uint8_t> reader = source;  // took the snapshot
  DirtyTiles dirty;
  dirty.reset({w, h, kGridTileSide});
  std::mt19937 rng(11);
  for (int patch = 0; patch < 40; ++patch) {
    dirty.clear();
    for (int k = 0; k < 12; ++k) {
      const int32_t x = static_cast<int32_t>(rng() % static_cast<uint32_t>(w));
      const int32_t y = static_cast<int32_t>(rng() % static_cast<uint32_t>(h));
      source[static_cast<size_t>(y * w + x)] = static_cast<uint8_t>(rng() % 8);
      dirty.mark(x, y);
    }
    encode_tiles(source, dirty, e);
    ASSERT_EQ(e.encoding, TileEncoding::XorRunLength) << "patch " << patch;
    EncodedTiles absolute;  // the same patch without the readers' cells
    encode_tiles(source, dirty, absolute);
    EXPECT_LT(e.data.size() * 3, absolute.data.size()) << "patch " << patch;
    ASSERT_TRUE(apply_tiles(view_of(e), reader, w, h)) << "patch " << patch;
    ASSERT_EQ(reader, source) << "patch " << patch;
    EXPECT_EQ(e.readers_cells, source);
  }
  // Whole tiles rewritten (a region re-rendered): the absolute coding wins again.
  dirty.mark_all();
  for (auto& c : source) c = static_cast<uint8_t>(c == 6 ? 0 : 6);
  encode_tiles(source, dirty, e);
  EXPECT_NE(e.encoding, TileEncoding::XorRunLength);
  ASSERT_TRUE(apply_tiles(view_of(e), reader, w, h));
  EXPECT_EQ(reader, source);
}

TEST(GridTiles, EmptyPatchChangesNothing) {
  DirtyTiles dirty;
  dirty.reset({40, 40, kGridTileSide});
  EncodedTiles e;
  const std::vector<uint8_t> source = room(40, 40);
  encode_tiles(source, dirty, e);
  EXPECT_TRUE(e.tiles.empty());
  EXPECT_TRUE(e.data.empty());
  std::vector<uint8_t> mirror(source.size(), 3);
  std::vector<CellBox> changed;
  ASSERT_TRUE(apply_tiles(view_of(e), mirror, 40, 40, &changed));
  EXPECT_EQ(mirror, std::vector<uint8_t>(source.size(), 3));
  EXPECT_TRUE(changed.empty());
}

// Every malformed patch is refused with a message naming the fault, and the grid is untouched.
TEST(GridTiles, BadInputIsRejectedWithAClearErrorAndNothingApplied) {
  const int32_t w = 70, h = 33;
  const std::vector<uint8_t> source = room(w, h);
  DirtyTiles dirty;
  dirty.reset({w, h, kGridTileSide});
  dirty.mark(0, 0);
  dirty.mark(69, 32);
  EncodedTiles good;
  encode_tiles(source, dirty, good);
  ASSERT_EQ(good.encoding, TileEncoding::RunLength);

  const auto expect_refused = [&](TilePatchView v, const char* what) {
    std::vector<uint8_t> mirror(source.size(), 0xaa);
    std::vector<CellBox> changed;
    const Status s = apply_tiles(v, mirror, w, h, &changed);
    ASSERT_FALSE(s) << what;
    EXPECT_NE(s.message().find(what), std::string::npos) << s.message();
    EXPECT_EQ(mirror, std::vector<uint8_t>(source.size(), 0xaa)) << what;
    EXPECT_TRUE(changed.empty()) << what;
  };
  TilePatchView v = view_of(good);
  v.side = 0;
  expect_refused(v, "tile side 0");
  v = view_of(good);
  v.side = 4096;
  expect_refused(v, "tile side 4096");
  v = view_of(good);
  v.encoding = 7;
  expect_refused(v, "unknown encoding 7");
  const std::vector<uint32_t> outside{0, 6};
  v = view_of(good);
  v.tiles = outside;
  expect_refused(v, "tile 6 is outside");
  const std::vector<uint32_t> unordered{5, 0};
  v = view_of(good);
  v.tiles = unordered;
  expect_refused(v, "not in ascending order");
  const std::vector<uint32_t> repeated{0, 0};
  v = view_of(good);
  v.tiles = repeated;
  expect_refused(v, "not in ascending order");
  std::vector<uint8_t> odd = good.data;
  odd.push_back(1);
  v = view_of(good);
  v.data = odd;
  expect_refused(v, "odd length");
  std::vector<uint8_t> short_runs(good.data.begin(), good.data.end() - 2);
  v = view_of(good);
  v.data = short_runs;
  expect_refused(v, "runs cover");
  std::vector<uint8_t> raw(good.cells() - 1, 1);
  v = {kGridTileSide, static_cast<uint8_t>(TileEncoding::Raw), good.tiles, raw};
  expect_refused(v, "the tiles hold");
  std::vector<uint8_t> wrong_grid(10);
  const Status s = apply_tiles(view_of(good), wrong_grid, w, h);
  EXPECT_FALSE(s);
  EXPECT_EQ(wrong_grid, std::vector<uint8_t>(10, 0));
}

}  // namespace
}  // namespace slam
