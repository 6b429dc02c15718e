#pragma once
// Keeps an exploring robot close to ground it is localised on: the simplest form of active SLAM.
// The mapper's pose correction reports how well each robot is known in the map
// (PoseCorrection.covariance: grown by odometry while the robot is not tied to the old map, shrunk
// by each tie). In new ground a robot can only match its own fresh trail, and its heading drift
// turns into position error as it drives on, until a loop closes (docs/mapping-quality.md, "Where
// the largest errors come from"). So once the uncertainty passes a limit, the robot goes back to the
// place where it was last tied; driving there over old ground ties it again (and bends the trail it
// just laid), then it explores on.
#include <limits>
#include <optional>

#include "common/core/result.hpp"
#include "planner/core/plan_types.hpp"

namespace slam::planner {

struct RelocaliseConfig {
  // An exploring robot less certain than this (m, the larger of its x and y sigmas) goes back to where it was
  // last tied to the map; 0: never (exploration ignores the pose correction's uncertainty).
  double return_sigma_m = 0.12;
  // A tie that makes a robot this certain (m) marks where it is as its place to return to.
  double tied_sigma_m = 0.06;
};

Status validate(const RelocaliseConfig& config);

class LocalisationWatch {
 public:
  // The robot's position uncertainty (m) as the pose correction last reported it. One that shrank
  // to within tied_sigma_m marks where the robot is as a place it was tied to the old map.
  void observe_uncertainty(double sigma_m, const RelocaliseConfig& config);
  // The robot's map-frame position.
  void observe_position(Vec2 position, const RelocaliseConfig& config);

  // Where to go back to now: the robot's uncertainty passed the limit and it was tied somewhere
  // before. Once per excursion: a return that does not tie the robot again is not repeated until
  // it is tied (a place that no longer matches would otherwise hold it forever).
  std::optional<Vec2> take_return(const RelocaliseConfig& config);
  bool tied(const RelocaliseConfig& config) const { return sigma_m_ <= config.tied_sigma_m; }
  double sigma_m() const { return sigma_m_; }
  std::optional<Vec2> tied_place() const { return tied_place_; }

 private:
  double sigma_m_ = std::numeric_limits<double>::infinity();  // unknown until reported
  std::optional<Vec2> position_;
  std::optional<Vec2> tied_place_;
  bool returned_ = false;  // a return was taken since the robot was last tied
};

}  // namespace slam::planner
