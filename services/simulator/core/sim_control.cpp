// Command checks and application. The Simulation validates physics values itself (noise, speed);
// this adds what only a command can get wrong: counts, ids, worlds, fleet size.
#include "simulator/core/sim_control.hpp"

#include <fmt/format.h>

#include "protocol/topic.hpp"
#include "simulator/core/world_loader.hpp"

namespace slam::sim {
namespace {

Result<ControlOutcome> spawn(Simulation& sim, const ControlCommand& c) {
  const size_t wanted = c.poses.empty() ? c.count : c.poses.size();
  if (!c.poses.empty() && c.count != 0 && c.count != c.poses.size())
    return Error{fmt::format("spawn: count {} does not match the {} poses given", c.count, c.poses.size())};
  if (wanted == 0) return Error{"spawn: count is 0 and no poses are given"};
  if (sim.robots().size() + wanted > kMaxFleet)
    return Error{fmt::format("spawn: {} more robots would make {}, limit {}", wanted,
                             sim.robots().size() + wanted, kMaxFleet)};
  if (!c.robot_id.empty()) {
    if (c.poses.size() != 1)
      return Error{
          fmt::format("spawn: robot id '{}' needs exactly one pose, got {}", c.robot_id, c.poses.size())};
    if (auto s = protocol::validate_robot_id(c.robot_id); !s) return Error{"spawn: " + s.detail()};
  }
  ControlOutcome out;
  if (c.poses.empty()) {
    auto ids = sim.spawn_random(wanted);
    if (!ids) return Error{"spawn: " + ids.message()};
    out.spawned = std::move(*ids);
    return out;
  }
  for (const Pose& p : c.poses) {
    auto id = sim.spawn(p, c.robot_id);
    if (!id) {
      for (const std::string& added : out.spawned) sim.remove(added);
      return Error{"spawn: " + id.message()};
    }
    out.spawned.push_back(std::move(*id));
  }
  return out;
}

}  // namespace

Result<ControlOutcome> apply_control(Simulation& sim, const ControlCommand& c) {
  ControlOutcome out;
  switch (c.kind) {
    case ControlKind::Spawn:
      return spawn(sim, c);
    case ControlKind::Remove:
      if (!sim.remove(c.robot_id)) return Error{fmt::format("remove: no simulated robot '{}'", c.robot_id)};
      out.removed.push_back(c.robot_id);
      return out;
    case ControlKind::Pause:
      sim.pause();
      return out;
    case ControlKind::Resume:
      sim.resume();
      return out;
    case ControlKind::SetWorld: {
      if (c.world.empty()) return Error{"set world: no world given"};
      auto world = load_world(c.world);
      if (!world) return Error{"set world: " + world.message()};
      if (auto s = sim.set_world(std::move(*world)); !s) return Error{"set world: " + s.message()};
      out.world_changed = true;
      return out;
    }
    case ControlKind::SetNoise:
      if (auto s = sim.set_noise(c.range_noise_sd, c.dropout, c.odometry_drift); !s)
        return Error{"set noise: " + s.message()};
      return out;
    case ControlKind::SetSpeed:
      if (auto s = sim.set_speed_factor(c.speed_factor); !s) return Error{"set speed: " + s.message()};
      return out;
  }
  return Error{fmt::format("command kind {} is unknown", static_cast<int>(c.kind))};
}

}  // namespace slam::sim
