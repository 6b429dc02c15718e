#include "pose_correction/correction_schedule.hpp"

#include <algorithm>

namespace slam::correction {

void CorrectionSchedule::begin_pass(size_t backlog, int64_t now_ns) {
  load_ = backlog >= options_.shed_backlog   ? Load::Shedding
          : backlog >= options_.load_backlog ? Load::Loaded
                                             : Load::Normal;
  // The allowance holds at most one second's worth, so a quiet spell does not buy a burst.
  if (last_refill_ns_ != std::numeric_limits<int64_t>::min() && now_ns > last_refill_ns_) {
    wide_tokens_ += static_cast<double>(now_ns - last_refill_ns_) * 1e-9 * options_.wide_per_s;
  }
  wide_tokens_ = std::min(wide_tokens_, std::max(1.0, options_.wide_per_s));
  if (last_refill_ns_ == std::numeric_limits<int64_t>::min() || now_ns > last_refill_ns_)
    last_refill_ns_ = now_ns;
}

bool CorrectionSchedule::allow_tie(RobotState& robot) {
  if (load_ == Load::Shedding) return false;
  ++robot.keyframes_since_tie;
  if (load_ == Load::Loaded && robot.keyframes_since_tie < options_.ties_every) return false;
  robot.keyframes_since_tie = 0;
  return true;
}

bool CorrectionSchedule::allow_wide(RobotState& robot, int64_t stamp_ns) {
  if (load_ == Load::Shedding) return false;
  if (load_ == Load::Normal) {
    robot.last_wide_ns = stamp_ns;
    return true;
  }
  const auto interval_ns = static_cast<int64_t>(options_.wide_interval_s * 1e9);
  const bool robot_due = robot.last_wide_ns == std::numeric_limits<int64_t>::min() ||
                         stamp_ns - robot.last_wide_ns >= interval_ns;
  if (!robot_due || wide_tokens_ < 1.0) return false;
  wide_tokens_ -= 1.0;
  robot.last_wide_ns = stamp_ns;
  return true;
}

void CorrectionSchedule::optimisation_landed(int64_t submitted_ns, int64_t landed_ns) {
  next_optimisation_ns_ =
      landed_ns + options_.optimise_idle_factor * std::max<int64_t>(0, landed_ns - submitted_ns);
}

}  // namespace slam::correction
