// Fleet stepping. Each step: index robot discs, pick random-walk targets, take the due scans from
// one consistent snapshot, then move every robot (walls and other robots stop it, never pass it).
#include "simulator/core/simulation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "simulator/core/kinematics.hpp"
#include "simulator/core/sensor.hpp"

namespace slam::sim {
namespace {

constexpr int kSpawnAttempts = 1000;
constexpr int kContactBisections = 8;     // stops within max_step / 256 of the contact point
constexpr double kRandomTargetMax = 3.0;  // m
constexpr double kRandomTargetMin = 0.3;  // m

std::mt19937_64 seeded(uint64_t seed, uint64_t stream) {
  std::seed_seq seq{static_cast<uint32_t>(seed), static_cast<uint32_t>(seed >> 32),
                    static_cast<uint32_t>(stream), static_cast<uint32_t>(stream >> 32)};
  return std::mt19937_64(seq);
}

}  // namespace

Result<Simulation> Simulation::create(World world, SimulationConfig config) {
  SLAM_TRY(validate(config));
  return Simulation(std::move(world), config);
}

Simulation::Simulation(World world, SimulationConfig config)
    : world_(std::move(world)), config_(config), spawn_rng_(seeded(config.seed, 0)) {
  rebuild_robot_index();
}

const Robot* Simulation::find(std::string_view id) const {
  for (const Robot& r : robots_)
    if (r.id == id) return &r;
  return nullptr;
}

bool Simulation::pose_free(Vec2 p, size_t ignore) const {
  if (!world_.is_free(p, config_.robot.radius)) return false;
  const double min_sq = 4.0 * config_.robot.radius * config_.robot.radius;
  for (size_t j = 0; j < robots_.size(); ++j) {
    const Vec2 d = p - robots_[j].true_pose.position();
    if (j != ignore && dot(d, d) < min_sq) return false;
  }
  return true;
}

Pose Simulation::odometry_start(const Pose& spawn) const {
  return config_.odom_frame == OdomFrame::Start ? Pose{} : spawn;
}

std::optional<Pose> Simulation::random_free_pose(const World& w, const std::vector<Vec2>& others) {
  const double r = config_.robot.radius;
  const Bounds& b = w.bounds();
  std::uniform_real_distribution<double> ux(b.min.x + r, b.max.x - r), uy(b.min.y + r, b.max.y - r);
  std::uniform_real_distribution<double> ua(-std::numbers::pi, std::numbers::pi);
  for (int attempt = 0; attempt < kSpawnAttempts; ++attempt) {
    const Vec2 p{ux(spawn_rng_), uy(spawn_rng_)};
    if (!w.is_free(p, r)) continue;
    const bool clear = std::none_of(others.begin(), others.end(), [&](Vec2 o) {
      const Vec2 d = p - o;
      return dot(d, d) < 4.0 * r * r;
    });
    if (clear) return Pose{p.x, p.y, ua(spawn_rng_)};
  }
  return std::nullopt;
}

Result<std::string> Simulation::spawn(Pose pose, std::string id) {
  if (!std::isfinite(pose.x) || !std::isfinite(pose.y) || !std::isfinite(pose.theta))
    return Error{"spawn pose is not finite"};
  // Serials are only used up by robots actually added, so ids do not depend on failed attempts.
  uint64_t serial = next_serial_;
  if (id.empty()) {
    id = fmt::format("sim-{}", serial);
    while (find(id)) id = fmt::format("sim-{}", ++serial);
  } else if (find(id)) {
    return Error{fmt::format("robot id '{}' is already in use", id)};
  }
  if (!pose_free({pose.x, pose.y}, robots_.size()))
    return Error{
        fmt::format("spawn pose ({:.3f}, {:.3f}) for '{}' is not free (wall, outside world '{}', or "
                    "another robot within {} m)",
                    pose.x, pose.y, id, world_.name(), 2.0 * config_.robot.radius)};
  next_serial_ = serial + 1;
  Robot r;
  r.id = id;
  r.serial = serial;
  pose.theta = wrap_angle(pose.theta);
  r.true_pose = pose;
  r.reported_pose = odometry_start(pose);
  r.rng = seeded(config_.seed, r.serial);
  r.next_report_s = time_s_ + std::uniform_real_distribution<double>(0.0, config_.report_period)(r.rng);
  robots_.push_back(std::move(r));
  rebuild_robot_index();
  return id;
}

Result<std::vector<std::string>> Simulation::spawn_random(size_t count) {
  std::vector<Vec2> others;
  for (const Robot& r : robots_) others.push_back(r.true_pose.position());
  std::vector<Pose> poses;
  for (size_t k = 0; k < count; ++k) {
    const auto p = random_free_pose(world_, others);
    if (!p)
      return Error{fmt::format("no free pose for robot {} of {} in world '{}' after {} attempts", k + 1,
                               count, world_.name(), kSpawnAttempts)};
    poses.push_back(*p);
    others.push_back({p->x, p->y});
  }
  std::vector<std::string> ids;
  for (const Pose& p : poses) {
    auto id = spawn(p);
    if (!id) return id.error();
    ids.push_back(std::move(*id));
  }
  return ids;
}

bool Simulation::remove(std::string_view id) {
  const auto it = std::find_if(robots_.begin(), robots_.end(), [&](const Robot& r) { return r.id == id; });
  if (it == robots_.end()) return false;
  robots_.erase(it);
  rebuild_robot_index();
  return true;
}

Status Simulation::set_world(World world) {
  std::vector<Vec2> placed;
  std::vector<Pose> poses;
  for (size_t k = 0; k < robots_.size(); ++k) {
    const auto p = random_free_pose(world, placed);
    if (!p)
      return Error{
          fmt::format("world '{}' has no free pose for robot {} of {}", world.name(), k + 1, robots_.size())};
    poses.push_back(*p);
    placed.push_back({p->x, p->y});
  }
  world_ = std::move(world);
  for (size_t k = 0; k < robots_.size(); ++k) {
    robots_[k].true_pose = poses[k];
    robots_[k].reported_pose = odometry_start(poses[k]);
    robots_[k].waypoint.reset();
  }
  rebuild_robot_index();
  return {};
}

Status Simulation::set_waypoint(std::string_view id, Vec2 target) {
  if (!std::isfinite(target.x) || !std::isfinite(target.y))
    return Error{fmt::format("waypoint for '{}' is not finite", id)};
  for (Robot& r : robots_) {
    if (r.id != id) continue;
    r.waypoint = target;
    r.waypoint_deadline_s = INFINITY;
    return {};
  }
  return Error{fmt::format("no simulated robot '{}'", id)};
}

Status Simulation::clear_waypoint(std::string_view id) {
  for (Robot& r : robots_) {
    if (r.id != id) continue;
    r.waypoint.reset();
    return {};
  }
  return Error{fmt::format("no simulated robot '{}'", id)};
}

Status Simulation::set_speed_factor(double factor) {
  SimulationConfig c = config_;
  c.speed_factor = factor;
  if (auto s = validate(c); !s) return s;
  config_ = c;
  return {};
}

Status Simulation::set_noise(double range_noise_sd, double dropout, double drift_per_metre) {
  SimulationConfig c = config_;
  c.sensor.range_noise_sd = range_noise_sd;
  c.sensor.dropout = dropout;
  c.odometry.drift_per_metre = drift_per_metre;
  if (auto s = validate(c); !s) return s;
  config_ = c;
  return {};
}

size_t Simulation::steps_for(double wall_seconds) {
  if (!(wall_seconds > 0.0)) return 0;
  // At most one wall second of backlog: after a stall the fleet resumes instead of racing.
  const double cap = config_.speed_factor;
  wall_backlog_s_ = std::min(wall_backlog_s_ + wall_seconds * config_.speed_factor, cap);
  const auto n = static_cast<size_t>(std::floor(wall_backlog_s_ / config_.dt));
  wall_backlog_s_ -= static_cast<double>(n) * config_.dt;
  return n;
}

void Simulation::rebuild_robot_index() {
  const GridGeometry& g = world_.grid();
  const double r = config_.robot.radius;
  robot_index_.reset(g.cells());
  for (size_t i = 0; i < robots_.size(); ++i) {
    const Vec2 p = robots_[i].true_pose.position();
    for_each_cell_in_box(g, {p.x - r, p.y - r}, {p.x + r, p.y + r},
                         [&](uint32_t cell) { robot_index_.add(cell, static_cast<uint32_t>(i)); });
  }
  robot_index_.finish();
}

double Simulation::cast(Vec2 origin, Vec2 dir, double max_range, size_t self) const {
  double best = world_.cast(origin, dir, max_range);
  traverse_ray(world_.grid(), origin, dir, best, [&](uint32_t cell, double t_exit) {
    for (uint32_t j : robot_index_.at(cell))
      if (j != self)
        best = std::min(best, ray_circle(origin, dir, robots_[j].true_pose.position(), config_.robot.radius));
    return best <= t_exit;
  });
  return best;
}

void Simulation::pick_random_target(Robot& r) {
  const RobotConfig& rc = config_.robot;
  std::uniform_real_distribution<double> ua(-std::numbers::pi, std::numbers::pi);
  for (int attempt = 0; attempt < 8; ++attempt) {
    const double a = ua(r.rng);
    const Vec2 dir{std::cos(a), std::sin(a)};
    const double free = world_.cast(r.true_pose.position(), dir, kRandomTargetMax + 2.0 * rc.radius);
    const double reach = std::min(free - 2.0 * rc.radius, kRandomTargetMax);
    if (reach < kRandomTargetMin) continue;
    const double d = std::uniform_real_distribution<double>(kRandomTargetMin, reach)(r.rng);
    // The target is reachable in the true world; the robot is told it in its odometry frame.
    r.waypoint = world_from_odom(r).inverse().transform(r.true_pose.position() + dir * d);
    r.waypoint_deadline_s = time_s_ + 2.0 * d / rc.max_linear + std::numbers::pi / rc.max_angular + 2.0;
    return;
  }
}

bool Simulation::robots_allow(size_t i, Vec2 from, Vec2 to) const {
  const double r = config_.robot.radius;
  const double min_sq = 4.0 * r * r;
  // The index is from the start of the step; robots moved since by at most one step each.
  const double margin = 2.0 * r + config_.robot.max_linear * config_.dt;
  bool allow = true;
  for_each_cell_in_box(world_.grid(), {to.x - margin, to.y - margin}, {to.x + margin, to.y + margin},
                       [&](uint32_t cell) {
                         for (uint32_t j : robot_index_.at(cell)) {
                           if (j == i) continue;
                           const Vec2 other = robots_[j].true_pose.position();
                           const Vec2 d_to = to - other, d_from = from - other;
                           // Only approaching is blocked, so robots that ended up touching can still part.
                           if (dot(d_to, d_to) < min_sq && dot(d_to, d_to) < dot(d_from, d_from))
                             allow = false;
                         }
                       });
  return allow;
}

void Simulation::move(size_t i) {
  Robot& r = robots_[i];
  if (!r.waypoint) return;
  const RobotConfig& rc = config_.robot;
  if (norm(*r.waypoint - r.reported_pose.position()) < rc.waypoint_tolerance) {
    r.waypoint.reset();
    return;
  }
  const Pose desired =
      integrate(r.true_pose, drive_command(r.reported_pose, *r.waypoint, config_.dt, rc), config_.dt);
  const Vec2 from = r.true_pose.position(), step = Vec2{desired.x, desired.y} - from;
  const auto allowed = [&](double f) {
    const Vec2 to = from + step * f;
    return world_.motion_clear(from, to, rc.radius) && robots_allow(i, from, to);
  };
  double fraction = 1.0;
  if ((step.x != 0.0 || step.y != 0.0) && !allowed(1.0)) {
    // Largest fraction of the step that stays clear: the robot stops at the obstacle.
    double lo = 0.0, hi = 1.0;
    for (int k = 0; k < kContactBisections; ++k) {
      const double mid = 0.5 * (lo + hi);
      (allowed(mid) ? lo : hi) = mid;
    }
    fraction = lo;
  }
  const Pose after{from.x + step.x * fraction, from.y + step.y * fraction, desired.theta};
  r.reported_pose = odometry_update(r.reported_pose, r.true_pose, after, config_.odometry, r.rng);
  r.true_pose = after;
  if (norm(*r.waypoint - r.reported_pose.position()) < rc.waypoint_tolerance) r.waypoint.reset();
}

void Simulation::count_contacts() {
  const double r = config_.robot.radius;
  const double reach = 2.0 * r + kContactGap;
  // The index is from the start of the step; robots moved since by at most one step each.
  const double margin = reach + config_.robot.max_linear * config_.dt;
  touching_now_.clear();
  for (size_t i = 0; i < robots_.size(); ++i) {
    const Vec2 p = robots_[i].true_pose.position();
    for_each_cell_in_box(world_.grid(), {p.x - margin, p.y - margin}, {p.x + margin, p.y + margin},
                         [&](uint32_t cell) {
                           for (uint32_t j : robot_index_.at(cell)) {
                             if (j <= i) continue;
                             const Vec2 d = robots_[j].true_pose.position() - p;
                             if (dot(d, d) >= reach * reach) continue;
                             const uint64_t a = robots_[i].serial, b = robots_[j].serial;
                             touching_now_.emplace_back(std::min(a, b), std::max(a, b));
                           }
                         });
  }
  // A pair indexed in several cells shows up once per cell.
  std::sort(touching_now_.begin(), touching_now_.end());
  touching_now_.erase(std::unique(touching_now_.begin(), touching_now_.end()), touching_now_.end());
  size_t k = 0;
  for (const auto& pair : touching_now_) {
    while (k < touching_.size() && touching_[k] < pair) ++k;
    if (k == touching_.size() || touching_[k] != pair) ++contacts_;
  }
  touching_.swap(touching_now_);
}

std::span<const RobotReport> Simulation::step() {
  if (paused_) return {};
  rebuild_robot_index();
  size_t due = 0;
  for (size_t i = 0; i < robots_.size(); ++i) {
    Robot& r = robots_[i];
    if (config_.random_walk && r.waypoint && time_s_ > r.waypoint_deadline_s) r.waypoint.reset();
    if (config_.random_walk && !r.waypoint) pick_random_target(r);
    if (time_s_ + 1e-9 < r.next_report_s) continue;
    if (due == reports_.size()) reports_.emplace_back();
    RobotReport& out = reports_[due++];
    out.robot_id = r.id;
    out.time_s = time_s_;
    out.reported_pose = r.reported_pose;
    out.true_pose = r.true_pose;
    scan(
        config_.sensor, r.true_pose, r.reported_pose, r.rng,
        [&](Vec2 o, Vec2 d, double m) { return cast(o, d, m, i); }, out);
    r.next_report_s += config_.report_period;
    if (r.next_report_s <= time_s_) r.next_report_s = time_s_ + config_.report_period;
  }
  for (size_t i = 0; i < robots_.size(); ++i) move(i);
  count_contacts();
  time_s_ += config_.dt;
  return {reports_.data(), due};
}

}  // namespace slam::sim
