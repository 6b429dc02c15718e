// Robots as the viewer knows them (see robot_registry.hpp).
#include "viewer/core/robot_registry.hpp"

#include <algorithm>

namespace slam::viewer {

RobotView& RobotRegistry::get_or_add(const std::string& id) {
  if (RobotView* r = find(id)) return *r;
  index_.emplace(id, robots_.size());
  auto& r = robots_.emplace_back(std::make_unique<RobotView>(id, max_points_));
  r->settings = defaults_;
  r->settings.color = default_robot_color(id);
  r->settings.color.a = defaults_.color.a;
  return *r;
}

RobotView* RobotRegistry::find(const std::string& id) {
  const auto it = index_.find(id);
  return it == index_.end() ? nullptr : robots_[it->second].get();
}

bool RobotRegistry::forget(const std::string& id) {
  pose_stamps_.forget(id);
  const auto it = index_.find(id);
  if (it == index_.end()) return false;
  const size_t at = it->second;
  robots_.erase(robots_.begin() + static_cast<std::ptrdiff_t>(at));
  index_.erase(it);
  for (auto& [other, position] : index_)
    if (position > at) --position;
  ++removals_;
  return true;
}

void RobotRegistry::ingest(const ObservationData& o) {
  RobotView& r = get_or_add(o.robot_id);
  ++r.observations;
  r.last_observed_pose = o.pose;
  const Pose map_from_odom = r.map_from_odom();
  placed_xy_.resize(o.hits_xy.size());
  for (size_t i = 0; i + 1 < o.hits_xy.size(); i += 2) {
    const Vec2 p = map_from_odom.transform({o.hits_xy[i], o.hits_xy[i + 1]});
    placed_xy_[i] = static_cast<float>(p.x);
    placed_xy_[i + 1] = static_cast<float>(p.y);
  }
  r.points.append(placed_xy_.data(), placed_xy_.size() / 2);
}

void RobotRegistry::ingest(msg::RobotState&& s) {
  const LatestStamps::Verdict verdict = pose_stamps_.judge(s.robot_id, s.last_seen_ns);
  if (verdict == LatestStamps::Verdict::Forgotten) return;
  RobotView& r = get_or_add(s.robot_id);
  if (verdict == LatestStamps::Verdict::Stale && r.has_state) {
    // A record older than the digest pose shown: its counters are news, its pose is not.
    s.pose = r.state.pose;
    s.has_heading = r.state.has_heading;
    s.online = r.state.online;
    s.last_seen_ns = r.state.last_seen_ns;
  }
  r.state = std::move(s);
  r.has_state = true;
}

void RobotRegistry::ingest(const msg::RobotPose& p) {
  if (pose_stamps_.judge(p.robot_id, p.last_seen_ns) != LatestStamps::Verdict::Fresh) return;
  RobotView& r = get_or_add(p.robot_id);
  r.state.robot_id = p.robot_id;
  r.state.pose = p.pose;
  r.state.has_heading = p.has_heading;
  r.state.online = p.online;
  r.state.last_seen_ns = p.last_seen_ns;
  r.has_state = true;
}

void RobotRegistry::ingest(msg::RobotPath&& p) {
  RobotView& r = get_or_add(p.robot_id);
  r.path = std::move(p);
  r.has_path = true;
}

namespace {

// Several writers keep a robot's mission (its sender and the planner reporting progress): a late
// joiner gets their samples in any order. Of the same mission, the one further along is kept.
bool behind(const msg::Mission& next, const msg::Mission& kept) {
  if (next.mission_id != kept.mission_id) return false;
  if ((next.status == MissionStatus::Active) != (kept.status == MissionStatus::Active))
    return next.status == MissionStatus::Active;
  return next.laps < kept.laps || (next.laps == kept.laps && next.current < kept.current);
}

}  // namespace

void RobotRegistry::ingest(msg::Mission&& m) {
  RobotView& r = get_or_add(m.robot_id);
  if (r.has_mission && behind(m, r.mission)) return;
  r.mission = std::move(m);
  r.has_mission = true;
}

void RobotRegistry::ingest(msg::PoseCorrection&& c) {
  RobotView& r = get_or_add(c.robot_id);
  if ((!r.has_correction || c.source == CorrectionSource::Operator) && !r.points.empty())
    r.points.move_all(c.map_from_odom.compose(r.map_from_odom().inverse()));
  r.correction = std::move(c);
  r.has_correction = true;
}

void RobotRegistry::apply_defaults_to_all() {
  for (auto& r : robots_) {
    const Rgba keep = r->settings.color;
    r->settings = defaults_;
    r->settings.color = {keep.r, keep.g, keep.b, defaults_.color.a};
  }
}

size_t RobotRegistry::online() const {
  return static_cast<size_t>(std::count_if(robots_.begin(), robots_.end(),
                                           [](const auto& r) { return r->has_state && r->state.online; }));
}

size_t RobotRegistry::total_points() const {
  size_t n = 0;
  for (const auto& r : robots_) n += r->points.size();
  return n;
}

bool RobotRegistry::bounds(WorldBox* box) const {
  bool any = false;
  auto add = [&](double x0, double y0, double x1, double y1) {
    if (!any) *box = {x0, y0, x1, y1};
    box->min_x = std::min(box->min_x, x0);
    box->min_y = std::min(box->min_y, y0);
    box->max_x = std::max(box->max_x, x1);
    box->max_y = std::max(box->max_y, y1);
    any = true;
  };
  for (const auto& r : robots_) {
    if (r->has_state) add(r->state.pose.x, r->state.pose.y, r->state.pose.x, r->state.pose.y);
    if (!r->points.empty()) {
      const WorldBox& b = r->points.bounds();
      add(b.min_x, b.min_y, b.max_x, b.max_y);
    }
  }
  return any;
}

}  // namespace slam::viewer
