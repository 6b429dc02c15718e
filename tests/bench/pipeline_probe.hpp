#pragma once
// The robot-to-map delay probe of bench_pipeline. Each probe is one v1 message from an extra robot
// ("probe") whose single obstacle point lies in a fresh cell below the world's bottom wall, where
// no simulated robot can see, so one hit turns that cell from unknown to occupied. The delay is
// the time from publishing the message to the first GridTiles patch (or GridSnapshot) showing the cell
// occupied. Probes sit in columns 7 cells apart and rows 15 apart, so no probe's ray crosses
// another probe's cell before that probe is sent.
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "common/core/geometry.hpp"
#include "common/fastdds/fast_topics.hpp"
#include "pipeline_rig.hpp"

namespace slam::bench {

class ProbeSet {
 public:
  // Up to `count` probes (at most capacity(grid)); their payloads are encoded here, once.
  ProbeSet(const GridLayout& grid, size_t count);

  static size_t capacity(const GridLayout& grid);
  size_t size() const { return probes_.size(); }
  const std::vector<uint8_t>& payload(size_t k) const { return probes_[k].payload; }

  // Records the monotonic time probe k was handed to MQTT; call right before publishing.
  void mark_sent(size_t k, int64_t monotonic_ns);

  // DDS listener callbacks: a snapshot sets the layout and the cells patches apply to.
  void on_snapshot(const GridSnapshot& snapshot);
  void on_patch(const GridTiles& patch);

  // Percentiles over every probe sent; one not seen yet counts with its age at `now` (a lower
  // bound), so lost or late probes raise the percentiles instead of vanishing from them.
  struct Summary {
    size_t sent = 0;
    size_t seen = 0;
    double p50_ms = -1.0;
    double p99_ms = -1.0;
    double max_ms = -1.0;
  };
  Summary summary(int64_t now_monotonic_ns) const;

  // Patches received and their serialized bytes (CDR payload), for the bandwidth the map stream costs.
  uint64_t patches() const { return patches_.load(); }
  uint64_t patch_bytes() const { return patch_bytes_.load(); }
  // Cells in the patches' tiles: what raw tiles would cost, to weigh the run-length coding.
  uint64_t patch_cells() const { return patch_cells_.load(); }

 private:
  struct Probe {
    double x = 0.0;  // the obstacle point (m), as the gateway will decode it
    double y = 0.0;
    std::vector<uint8_t> payload;
    int64_t sent_ns = 0;    // 0: not sent yet
    int64_t delay_ns = -1;  // -1: not seen yet
  };
  struct Layout {
    uint32_t id = 0;
    uint32_t width = 0;
    uint32_t height = 0;
    double origin_x = 0.0;
    double origin_y = 0.0;
    double resolution = 0.0;
  };

  // Marks every sent, unseen probe whose cell lies in `box` and is occupied in cells_.
  void check_box(const CellBox& box, int64_t now);

  GridLayout grid_;
  mutable std::mutex mutex_;
  std::vector<Probe> probes_;
  std::optional<Layout> layout_;
  std::vector<uint8_t> cells_;    // the grid as patches leave it
  std::vector<CellBox> changed_;  // the tiles of the patch being applied
  std::atomic<uint64_t> patches_{0};
  std::atomic<uint64_t> patch_bytes_{0};
  std::atomic<uint64_t> patch_cells_{0};
};

}  // namespace slam::bench
