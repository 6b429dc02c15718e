#pragma once
// Operator commands (SimControl on DDS) in plain form, and their application to a Simulation. Every
// value is checked first: a bad command changes nothing and the error says what was wrong.
#include <cstdint>
#include <string>
#include <vector>

#include "common/core/result.hpp"
#include "simulator/core/geometry.hpp"
#include "simulator/core/simulation.hpp"

namespace slam::sim {

enum class ControlKind : uint8_t { Spawn, Remove, Pause, Resume, SetWorld, SetNoise, SetSpeed };

struct ControlCommand {
  uint64_t command_id = 0;
  ControlKind kind = ControlKind::Pause;
  uint32_t count = 0;       // Spawn: robots at random free poses (poses empty) or 0 / poses.size()
  std::vector<Pose> poses;  // Spawn: explicit poses
  std::string robot_id;     // Remove: which; Spawn: the id of a single robot at one explicit pose
  std::string world;        // SetWorld: built-in name or file (see load_world)
  double range_noise_sd = 0.0;
  double dropout = 0.0;
  double odometry_drift = 0.0;
  double speed_factor = 1.0;
};

// What a command changed, so the service can open or close robot connections and republish.
struct ControlOutcome {
  std::vector<std::string> spawned;
  std::vector<std::string> removed;
  bool world_changed = false;
};

// Largest fleet one simulator runs; a spawn beyond it is refused (a typo, not a load test).
inline constexpr size_t kMaxFleet = 5000;

// Applies `command`. Spawns are all-or-none and robot ids must be valid MQTT robot ids (they become
// topic levels). Errors name the command and the bad value.
Result<ControlOutcome> apply_control(Simulation& sim, const ControlCommand& command);

}  // namespace slam::sim
