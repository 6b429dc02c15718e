#pragma once
// The mapper's side of the map stream, played at random for tests of its readers: a grid whose cells
// change at random places, encoded one patch at a time with the shared tile codec.
#include <cstdint>
#include <random>
#include <vector>

#include "common/core/grid_tiles.hpp"

namespace slam::testkit {

class RandomTileSource {
 public:
  RandomTileSource(int32_t width, int32_t height, uint8_t initial, uint32_t seed)
      : width_(width), height_(height), cells_(static_cast<size_t>(width) * height, initial), rng_(seed) {
    dirty_.reset({width, height, kGridTileSide});
  }

  // Changes `changes` random cells to occupied or free and returns them encoded as changed tiles.
  const EncodedTiles& next_patch(int changes = 40) {
    for (int k = 0; k < changes; ++k) {
      const auto x = static_cast<int32_t>(rng_() % static_cast<uint32_t>(width_));
      const auto y = static_cast<int32_t>(rng_() % static_cast<uint32_t>(height_));
      cells_[static_cast<size_t>(y) * width_ + x] = static_cast<uint8_t>(1 + rng_() % 2);
      dirty_.mark(x, y);
    }
    encode_tiles(cells_, dirty_, encoded_);
    dirty_.clear();
    return encoded_;
  }

  const std::vector<uint8_t>& cells() const { return cells_; }

 private:
  int32_t width_;
  int32_t height_;
  std::vector<uint8_t> cells_;
  std::mt19937 rng_;
  DirtyTiles dirty_;
  EncodedTiles encoded_;
};

}  // namespace slam::testkit
