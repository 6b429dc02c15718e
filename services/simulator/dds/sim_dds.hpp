#pragma once
// The simulator's DDS edge on Cyclone DDS (C API, idlc types): SimControl in, SimReply, SimWorld
// and SimGroundTruth out, with QoS only from topics.hpp. Converts between the IDL structs and the
// core's plain types here and nowhere else. Used from the simulation loop's thread only.
#include <dds/dds.h>
#include <slam/cyclone/sim.h>

#include <memory>
#include <string>
#include <vector>

#include "common/core/result.hpp"
#include "common/cyclone/dds.hpp"
#include "simulator/core/sim_control.hpp"
#include "simulator/core/simulation.hpp"
#include "simulator/core/world.hpp"

namespace slam::sim {

// A control sample that could not become a command (an unknown kind): still answered by its id.
struct UnreadableControl {
  uint64_t command_id = 0;
  std::string error;
};

class SimDds {
 public:
  // Participant on `domain`, the control reader and the reply/world/truth writers; fails naming the
  // entity.
  static Result<std::unique_ptr<SimDds>> create(int domain);

  dds_entity_t participant() const { return participant_.get(); }

  // Control commands received since the last call, appended to `out`; samples that cannot become
  // a command go to `unreadable`.
  Status take_controls(std::vector<ControlCommand>& out, std::vector<UnreadableControl>& unreadable);

  // The answer to command `command_id`: ok, or `result`'s message (cut to 512 bytes).
  Status publish_reply(uint64_t command_id, const Status& result);

  // The hidden world (transient-local: late joiners get it too). Names beyond 256 bytes are cut.
  Status publish_world(const World& world);
  // True and believed pose of every robot, stamped now.
  Status publish_truth(const Simulation& sim);

 private:
  SimDds() = default;

  cyclone::Entity participant_;
  dds_entity_t control_reader_ = 0;  // children of the participant: deleted with it
  dds_entity_t reply_writer_ = 0;
  dds_entity_t world_writer_ = 0;
  dds_entity_t truth_writer_ = 0;
  std::vector<slam_Segment2> walls_;
  std::vector<slam_SimRobotTruth> truth_;
};

}  // namespace slam::sim
