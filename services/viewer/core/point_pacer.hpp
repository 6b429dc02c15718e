#pragma once
// How many points the next step of the point texture's re-render may rasterise. A fixed count
// cannot bound a frame: the cost of a point differs by an order of magnitude between renderers
// (a GPU, llvmpipe), point sizes and the machine's load. So the pacer learns from the frames
// themselves: their base time (frames that rasterised next to nothing) and, from frames that did,
// the time per point; the next step gets as many points as fit between the base and the target
// frame time, and at most twice the last measured step. Frame times, not GL timer queries: llvmpipe's
// GL_TIME_ELAPSED reads about 0 for the first step after the texture is cleared, and what the operator sees
// is the whole frame anyway.
#include <cstdint>

#include "common/core/result.hpp"

namespace slam::viewer {

struct PacerConfig {
  double frame_ms = 60.0;           // what a frame with a re-render step should take
  uint64_t max_points = 2'000'000;  // never more per step (--point-budget)
  uint64_t min_points = 5'000;      // never fewer, so a re-render always progresses
  uint64_t first_points = 50'000;   // before anything was measured
};

// Ok, or which setting is out of range.
Status validate(const PacerConfig& c);

class PointPacer {
 public:
  // `config` must be valid.
  explicit PointPacer(const PacerConfig& config);

  // Points the next step may rasterise.
  uint64_t budget() const { return budget_; }
  // A finished frame: it rasterised `points` into the texture and took `ms` (its work and the
  // buffer swap, not a frame-rate cap's sleep). Frames under min_points update the base time.
  void record(uint64_t points, double ms);

  double base_ms() const { return base_ms_; }
  // The current estimate; meaningful once a step was measured.
  double ms_per_point() const { return ms_per_point_; }

 private:
  void update_budget();

  PacerConfig config_;
  double base_ms_ = 0.0;  // 0 until a light frame was seen: every millisecond counts as points'
  bool have_base_ = false;
  double ms_per_point_ = 0.0;
  bool have_cost_ = false;
  uint64_t last_step_points_ = 0;
  uint64_t budget_ = 0;
};

}  // namespace slam::viewer
