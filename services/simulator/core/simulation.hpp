#pragma once
// The fleet: N simulated robots in one world, stepped with a fixed dt. Owns spawning (given or
// random free poses), removal, pause, random-walk targets, wall and robot-robot collisions, and
// the reports due each step. Deterministic for a seed: robot k draws from its own generator.
#include <cstdint>
#include <optional>
#include <random>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/core/result.hpp"
#include "simulator/core/config.hpp"
#include "simulator/core/grid.hpp"
#include "simulator/core/report.hpp"
#include "simulator/core/world.hpp"

namespace slam::sim {

struct Robot {
  std::string id;
  uint64_t serial = 0;  // spawn order from 1; seeds the generator with the simulation seed
  Pose true_pose;
  Pose reported_pose;  // odometry estimate, in the robot's odometry frame (see OdomFrame); waypoints too
  std::optional<Vec2> waypoint;
  double waypoint_deadline_s = 0.0;  // random walk gives up on a target after this time
  double next_report_s = 0.0;
  std::mt19937_64 rng;
};

// Where the robot's odometry frame lies in the world now, drift included: world <- odom.
inline Pose world_from_odom(const Robot& r) {
  return r.true_pose.compose(r.reported_pose.inverse());
}

class Simulation {
 public:
  static Result<Simulation> create(World world, SimulationConfig config);

  const World& world() const { return world_; }
  const SimulationConfig& config() const { return config_; }
  double time() const { return time_s_; }
  std::span<const Robot> robots() const { return robots_; }
  const Robot* find(std::string_view id) const;

  // Places a robot at `pose` in the world; its odometry starts there (OdomFrame::World) or at
  // (0, 0, 0) (OdomFrame::Start). An empty id becomes "sim-<serial>". Fails when
  // the id is taken or the pose is not free (in a wall, off the world, overlapping a robot).
  Result<std::string> spawn(Pose pose, std::string id = {});
  // `count` robots at random free poses with random headings; all or none are added.
  Result<std::vector<std::string>> spawn_random(size_t count);
  // False when no robot has that id.
  bool remove(std::string_view id);
  // Replaces the world and moves every robot to a random free pose (ids kept, odometry restarted
  // as at a spawn).
  Status set_world(World world);

  // Target in the robot's own odometry frame, as a server sends it.
  Status set_waypoint(std::string_view id, Vec2 target);
  Status clear_waypoint(std::string_view id);

  void pause() { paused_ = true; }
  void resume() { paused_ = false; }
  bool paused() const { return paused_; }
  Status set_speed_factor(double factor);
  // Range noise (m), dropout probability, odometry drift per metre; validated together.
  Status set_noise(double range_noise_sd, double dropout, double drift_per_metre);

  // Whole steps to run for `wall_seconds` of real time at the speed factor (the remainder carries).
  size_t steps_for(double wall_seconds);

  // Advances one step of dt (nothing while paused) and returns the reports due in it, valid until
  // the next call. No allocation once every robot has reported once.
  std::span<const RobotReport> step();

  // Nearest obstacle along a unit-length beam: walls and other robots' discs (robot index `self`
  // is ignored); max_range when nothing is closer.
  double cast(Vec2 origin, Vec2 dir, double max_range, size_t self) const;

  // Robot-robot contacts since the start: a pair whose discs come within kContactGap of each other
  // (motion stops robots at touching, never past it) counts once, and again only after it parted.
  uint64_t contacts() const { return contacts_; }
  static constexpr double kContactGap = 0.005;  // m

 private:
  Simulation(World world, SimulationConfig config);
  bool pose_free(Vec2 p, size_t ignore) const;
  Pose odometry_start(const Pose& spawn) const;
  std::optional<Pose> random_free_pose(const World& w, const std::vector<Vec2>& others);
  void rebuild_robot_index();
  void pick_random_target(Robot& r);
  void move(size_t i);
  bool robots_allow(size_t i, Vec2 from, Vec2 to) const;
  void count_contacts();

  World world_;
  SimulationConfig config_;
  std::mt19937_64 spawn_rng_;
  std::vector<Robot> robots_;
  Buckets robot_index_;
  std::vector<RobotReport> reports_;
  double time_s_ = 0.0;
  double wall_backlog_s_ = 0.0;
  uint64_t next_serial_ = 1;
  bool paused_ = false;
  // Pairs of robot serials (lower first) in contact after the last step, sorted; reused buffers.
  std::vector<std::pair<uint64_t, uint64_t>> touching_, touching_now_;
  uint64_t contacts_ = 0;
};

}  // namespace slam::sim
