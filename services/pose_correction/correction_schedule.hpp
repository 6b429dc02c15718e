#pragma once
// How much of the optional matching work around each keyframe PoseCorrector does, by load. Tracking
// (each keyframe against the map near its prediction) is what keeps a robot on the map; a tie to the
// old map and a wide loop-closure search are extras that tighten it. With a few robots everything
// runs for every keyframe. When closed keyframes pile up faster than they are matched (a fleet of
// hundreds), the extras degrade first, in steps, and each step is counted:
//  - loaded (backlog >= load_backlog): a robot ties only every `ties_every`-th keyframe, searches
//    the wide window at most every `wide_interval_s` (its own clock) and the fleet at most
//    `wide_per_s` times per second (a wide search costs about twenty narrow ones);
//  - shedding (backlog >= shed_backlog): tracking only;
//  - overflow (backlog > max_backlog): the oldest keyframes are placed by odometry alone, so the
//    observations they hold reach the map and memory stays bounded.
// Optimisations, whatever the load, keep a duty cycle: a solve costs more the larger the graph (a
// fleet adds a thousand keyframes a second), so the next one starts only after the last one's
// duration times optimise_idle_factor has passed since it landed.
// Plain data, no clock of its own: the caller passes the observations' time. Deterministic.
#include <cstddef>
#include <cstdint>
#include <limits>

namespace slam::correction {

struct ScheduleOptions {
  int max_keyframes_per_pass = 256;  // keyframes handed to matching per process() call
  size_t load_backlog = 64;          // closed keyframes waiting (or in matching): extras degrade
  size_t shed_backlog = 512;         // ...tracking only
  size_t max_backlog = 4096;         // ...beyond this many, place by odometry alone
  int ties_every = 4;                // loaded: a robot ties every k-th keyframe
  double wide_interval_s = 10.0;     // loaded: a robot's wide searches at least this far apart
  double wide_per_s = 20.0;          // loaded: wide searches per second, whole fleet
  int optimise_idle_factor = 4;      // after an optimisation, none for this many times its duration
};

enum class Load : uint8_t { Normal, Loaded, Shedding };

class CorrectionSchedule {
 public:
  // Per robot: what its rate limits remember.
  struct RobotState {
    int keyframes_since_tie = 0;
    int64_t last_wide_ns = std::numeric_limits<int64_t>::min();
  };

  explicit CorrectionSchedule(const ScheduleOptions& options = {}) : options_(options) {}

  // At the start of a pass: `backlog` keyframes wait or are being matched; `now_ns` refills the
  // fleet's wide-search allowance.
  void begin_pass(size_t backlog, int64_t now_ns);
  Load load() const { return load_; }
  // Keyframes to start matching this pass.
  int pass_budget() const { return options_.max_keyframes_per_pass; }
  // Of `waiting` closed keyframes, how many to place by odometry alone now.
  size_t overflow(size_t waiting) const {
    return waiting > options_.max_backlog ? waiting - options_.max_backlog : 0;
  }
  // Whether a keyframe of this robot near old map may try a tie (counts the keyframe either way).
  bool allow_tie(RobotState& robot);
  // Whether a keyframe (of time `stamp_ns`) that needs a wide search may have one; takes the
  // allowance when it may.
  bool allow_wide(RobotState& robot, int64_t stamp_ns);
  // An optimisation submitted at `submitted_ns` landed at `landed_ns`; whether one may start now.
  void optimisation_landed(int64_t submitted_ns, int64_t landed_ns);
  bool allow_optimisation(int64_t now_ns) const { return now_ns >= next_optimisation_ns_; }

 private:
  ScheduleOptions options_;
  Load load_ = Load::Normal;
  double wide_tokens_ = 0.0;
  int64_t last_refill_ns_ = std::numeric_limits<int64_t>::min();
  int64_t next_optimisation_ns_ = std::numeric_limits<int64_t>::min();
};

}  // namespace slam::correction
