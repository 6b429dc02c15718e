// Fuzz target for the map stream's tile decoder (apply_tiles): the input is a small grid's size,
// a tile side, an encoding, tile indices and the data, as a reader would receive them. A refused
// patch must leave the grid untouched; an accepted one, re-encoded, must apply to the same cells.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <vector>

#include "common/core/grid_tiles.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // Header: width, height, tile side, encoding, tile count; then 2 octets per tile (little endian).
  if (size < 5) return 0;
  const int32_t width = data[0] % 100 + 1;
  const int32_t height = data[1] % 100 + 1;
  const uint32_t side = data[2];  // 0 and large sides must be refused, not crash
  const uint8_t encoding = data[3];
  const size_t count = data[4];
  size_t pos = 5;
  std::vector<uint32_t> tiles;
  for (size_t i = 0; i < count && pos + 1 < size; ++i, pos += 2)
    tiles.push_back(uint32_t{data[pos]} | (uint32_t{data[pos + 1]} << 8));
  const std::span<const uint8_t> payload(data + pos, size - pos);

  std::vector<uint8_t> before(static_cast<size_t>(width) * static_cast<size_t>(height));
  for (size_t i = 0; i < before.size(); ++i) before[i] = static_cast<uint8_t>(i * 7);
  std::vector<uint8_t> cells = before;
  std::vector<slam::CellBox> changed;
  const slam::TilePatchView patch{side, encoding, tiles, payload};
  if (!slam::apply_tiles(patch, cells, width, height, &changed)) {
    if (cells != before || !changed.empty()) std::abort();
    return 0;
  }
  if (changed.size() != tiles.size()) std::abort();

  // Re-encode the applied tiles from the result and apply them to the original grid.
  slam::DirtyTiles dirty;
  dirty.reset({width, height, static_cast<int32_t>(side)});
  for (const slam::CellBox& box : changed) dirty.mark(box.x0, box.y0);
  slam::EncodedTiles encoded;
  slam::encode_tiles(cells, dirty, encoded);
  std::vector<uint8_t> again = before;
  const slam::TilePatchView round{side, static_cast<uint8_t>(encoded.encoding), encoded.tiles, encoded.data};
  if (!slam::apply_tiles(round, again, width, height) || again != cells) std::abort();
  return 0;
}
