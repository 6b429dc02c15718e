#include "mapper/core/correction_stage.hpp"

#include <cmath>
#include <utility>

#include "mapper/core/map_error.hpp"

namespace slam::mapper {

namespace {
constexpr size_t kMaxSpare = 4096;          // recycled observation records kept for reuse
constexpr int64_t kRerenderDutyFactor = 4;  // idle time after a re-render, in multiples of its duration
}  // namespace

CorrectionStage::CorrectionStage(bool enabled, const correction::CorrectorOptions& options)
    : enabled_(enabled),
      localise_only_(options.localise_only),
      rerender_shift_m_(options.rerender_shift_m),
      corrector_(options) {}

Status CorrectionStage::restore(Mapper& mapper) {
  if (!enabled_) return Status::ok();
  if (localise_only_) {
    spdlog::info("pose correction: localising only on the map: every robot is searched for on it");
    return Status::ok();  // the store's keyframes are the mapping run's, not where the robots are now
  }
  auto stored = mapper.load_keyframes();
  if (!stored) return stored.error();
  std::vector<correction::KeyframeCorrection> keyframes;
  keyframes.reserve(stored->size());
  for (const Keyframe& k : *stored)
    keyframes.push_back({k.id, k.robot_id, k.segment, k.odom, k.map_from_odom});
  corrector_.restore(keyframes);
  if (!keyframes.empty())
    spdlog::info("pose correction: restored {} keyframes from the store", keyframes.size());
  return Status::ok();
}

void CorrectionStage::add(Mapper& mapper, const RobotScan& scan, int64_t now_mono_ns) {
  if (!enabled_) return mapper.integrate(scan, now_mono_ns);
  const ObservationView& v = scan.view;
  auto keyframe =
      corrector_.add(scan.robot_id, scan.stamp_ns, Pose{v.x, v.y, v.theta}, v.has_heading, v.hits,
                     scan.robot_stamp_ns != 0 ? std::optional<int64_t>(scan.robot_stamp_ns) : std::nullopt);
  if (!keyframe) return mapper.reject(scan.robot_id, scan.seq, keyframe.message());
  // Recycled records: their strings and point buffers keep their capacity (no allocation per message).
  Held held;
  if (!spare_.empty()) {
    held = std::move(spare_.back());
    spare_.pop_back();
  }
  held.assign(scan.robot_id, scan.seq, scan.stamp_ns, v, scan.robot_stamp_ns);
  held_[*keyframe].push_back(std::move(held));
  ++held_observations_;
}

void CorrectionStage::save(Mapper& mapper, std::span<const correction::KeyframeCorrection> keyframes) {
  keyframes_.clear();
  for (const auto& k : keyframes)
    if (!k.discarded) keyframes_.push_back({k.id, k.robot, k.segment, k.odom, k.correction});
  if (auto s = mapper.save_keyframes(keyframes_); !s)
    log_.warn("save", "pose correction: keyframes not stored: {}", s.message());
}

void CorrectionStage::step(Mapper& mapper, int64_t now_ns, int64_t now_mono_ns) {
  if (!enabled_) return;
  const OccupancyGrid& grid = mapper.grid();
  corrector_.set_map_given(mapper.has_prior());
  finalised_.clear();
  corrector_.process(correction::GridView{grid.geometry(), grid.classes()}, now_ns, finalised_);
  if (!finalised_.empty()) {
    if (!localise_only_) save(mapper, finalised_);  // before the observations that reference them
    for (const auto& k : finalised_) {
      const auto it = held_.find(k.id);
      if (it == held_.end()) continue;
      if (k.discarded) {
        dropped_observations_ += static_cast<int64_t>(it->second.size());  // an unplaced robot's: not drawn
      } else if (localise_only_) {
        localised_observations_ += static_cast<int64_t>(it->second.size());
      } else {
        for (const Held& h : it->second) {
          mapper.integrate(
              RobotScan{h.robot_id, h.seq, h.stamp_ns, h.view(), k.id, k.correction, h.robot_stamp_ns},
              now_mono_ns);
        }
      }
      held_observations_ -= static_cast<int64_t>(it->second.size());
      for (Held& h : it->second) {
        if (spare_.size() < kMaxSpare) spare_.push_back(std::move(h));
      }
      held_.erase(it);
    }
  }
  moved_.clear();
  const double shift = corrector_.take_optimised(moved_);
  if (!moved_.empty()) {
    save(mapper, moved_);
    if (shift >= rerender_shift_m_) {
      spdlog::info(
          "pose correction: graph optimised, {} keyframes moved (up to {:.3f} m): the map is re-rendered",
          moved_.size(), shift);
      rerender_due_ = true;
    }
  }
  rerender_when_due(mapper, now_mono_ns);
}

void CorrectionStage::rerender_when_due(Mapper& mapper, int64_t now_mono_ns) {
  // A re-render redraws the tiles of the keyframes that moved (the whole grid when a closure moves
  // much of it), while with hundreds of robots optimisations land every few hundred milliseconds.
  // One starts only after the last one took a fifth of the time since it started: re-rendering
  // takes at most a fifth of a core, and the keyframes moved meanwhile join the next one (their
  // corrections are stored at once; only the grid waits).
  if (rerender_started_ns_ && !mapper.rebuilding()) {
    next_rerender_ns_ = now_mono_ns + kRerenderDutyFactor * (now_mono_ns - *rerender_started_ns_);
    rerender_started_ns_.reset();
  }
  if (!rerender_due_ || rerender_started_ns_ || now_mono_ns < next_rerender_ns_) return;
  rerender_due_ = false;
  rerender_started_ns_ = now_mono_ns;
  mapper.rerender();
}

Status CorrectionStage::set_initial_pose(const Mapper& mapper, std::string_view robot, const Pose& map_pose) {
  if (!enabled_) return Error{"pose correction is off (slam-mapper --slam off)", MapError::InvalidRequest};
  Status placed = [&]() -> Status {
    if (!std::isfinite(map_pose.x) || !std::isfinite(map_pose.y) || !std::isfinite(map_pose.theta))
      return Error{"initial pose is not finite"};
    const GridGeometry g = mapper.grid().geometry();
    if (!g.cell_at(map_pose.position())) {
      return Error{fmt::format(
          "initial pose ({:.2f}, {:.2f}) lies outside the map [{:.2f}, {:.2f}] x [{:.2f}, {:.2f}]",
          map_pose.x, map_pose.y, g.origin.x, g.origin.x + g.width * g.resolution, g.origin.y,
          g.origin.y + g.height * g.resolution)};
    }
    return corrector_.set_initial_pose(robot, map_pose);
  }();
  if (placed) return placed;
  // A robot the corrector has not heard from is the cause first, whatever else the pose has wrong.
  return Error{placed.message(), corrector_.knows(robot) ? MapError::InvalidRequest : MapError::UnknownRobot};
}

Status CorrectionStage::answer_placement(std::string_view robot, bool accept) {
  if (!enabled_) return Error{"pose correction is off (slam-mapper --slam off)", MapError::InvalidRequest};
  Status answered = corrector_.answer_placement(robot, accept);
  if (answered) return answered;
  return Error{answered.message(),
               corrector_.knows(robot) ? MapError::InvalidRequest : MapError::UnknownRobot};
}

size_t CorrectionStage::reset_robot(std::string_view robot) {
  if (!enabled_) return 0;
  for (auto it = held_.begin(); it != held_.end();) {
    if (!it->second.empty() && it->second.front().robot_id == robot) {
      held_observations_ -= static_cast<int64_t>(it->second.size());
      for (Held& h : it->second) {
        if (spare_.size() < kMaxSpare) spare_.push_back(std::move(h));
      }
      it = held_.erase(it);
    } else {
      ++it;
    }
  }
  const size_t removed = corrector_.reset_robot(robot);
  spdlog::info("pose correction: robot {} reset, {} keyframes left the pose graph", robot, removed);
  return removed;
}

void CorrectionStage::take_changed(std::vector<correction::RobotCorrection>& out) {
  corrector_.take_changed(out);
}

}  // namespace slam::mapper
