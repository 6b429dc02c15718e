#pragma once
// The inflation ("restricted") layer: for every cell, how many occupied cells lie within the robot
// radius. Kept incrementally: when one cell turns occupied (or stops being) only its disk of
// neighbours changes, so a scan costs O(changed cells x disk), never a full-grid pass.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace slam::mapper {

class InflationLayer {
 public:
  // radius in metres at `resolution`; the disk holds offsets whose cell centres lie within it
  // (radius 0: only the cell itself).
  void configure(double radius, double resolution);
  // Sizes the count array for a new layout and zeroes it (callers re-add occupied cells).
  void reset(int32_t width, int32_t height);

  // Occupied cell (x, y) appears: counts in its disk go up; on_first(index) for cells that were 0.
  template <class F>
  void add(int32_t x, int32_t y, F&& on_first) {
    for (const Offset& o : disk_) {
      const int32_t nx = x + o.dx;
      const int32_t ny = y + o.dy;
      if (nx < 0 || ny < 0 || nx >= width_ || ny >= height_) continue;
      const size_t i = static_cast<size_t>(ny) * static_cast<size_t>(width_) + static_cast<size_t>(nx);
      if (counts_[i]++ == 0) on_first(i);
    }
  }

  // Occupied cell (x, y) disappears: counts go down; on_last(index) for cells that reach 0.
  template <class F>
  void remove(int32_t x, int32_t y, F&& on_last) {
    for (const Offset& o : disk_) {
      const int32_t nx = x + o.dx;
      const int32_t ny = y + o.dy;
      if (nx < 0 || ny < 0 || nx >= width_ || ny >= height_) continue;
      const size_t i = static_cast<size_t>(ny) * static_cast<size_t>(width_) + static_cast<size_t>(nx);
      if (--counts_[i] == 0) on_last(i);
    }
  }

  bool inflated(size_t index) const { return counts_[index] != 0; }
  uint16_t count(size_t index) const { return counts_[index]; }

 private:
  struct Offset {
    int32_t dx;
    int32_t dy;
  };
  std::vector<Offset> disk_;
  std::vector<uint16_t> counts_;
  int32_t width_ = 0;
  int32_t height_ = 0;
};

}  // namespace slam::mapper
