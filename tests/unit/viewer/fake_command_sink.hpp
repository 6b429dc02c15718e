#pragma once
// A CommandSink that records every command instead of publishing it: ids count up from 1, or
// every send is refused (returns 0) while `refuse` is set.
#include <cstdint>
#include <vector>

#include "viewer/core/commands.hpp"

namespace slam::viewer {

class FakeCommandSink final : public CommandSink {
 public:
  uint64_t send(const GoalCommand& c) override { return record(goals, c); }
  uint64_t send(const MapEditCommand& c) override { return record(edits, c); }
  uint64_t send(const GridConfigCommand& c) override { return record(grid_configs, c); }
  uint64_t send(const MqttRequestCommand& c) override { return record(mqtt, c); }
  uint64_t send(const SimCommand& c) override { return record(sim, c); }
  uint64_t send(const MapFileCommand& c) override { return record(map_files, c); }
  uint64_t send(const InitialPoseCommand& c) override { return record(initial_poses, c); }
  uint64_t send(const PlacementAnswerCommand& c) override { return record(placement_answers, c); }
  uint64_t send(const ForgetCommand& c) override { return record(forgets, c); }
  uint64_t send(const PathPreviewCommand& c) override { return record(path_previews, c); }
  uint64_t send(const MissionCommand& c) override { return record(missions, c); }

  size_t total() const {
    return goals.size() + edits.size() + grid_configs.size() + mqtt.size() + sim.size() + map_files.size() +
           initial_poses.size() + placement_answers.size() + forgets.size() + path_previews.size() +
           missions.size();
  }

  std::vector<GoalCommand> goals;
  std::vector<MapEditCommand> edits;
  std::vector<GridConfigCommand> grid_configs;
  std::vector<MqttRequestCommand> mqtt;
  std::vector<SimCommand> sim;
  std::vector<MapFileCommand> map_files;
  std::vector<InitialPoseCommand> initial_poses;
  std::vector<PlacementAnswerCommand> placement_answers;
  std::vector<ForgetCommand> forgets;
  std::vector<PathPreviewCommand> path_previews;
  std::vector<MissionCommand> missions;
  bool refuse = false;
  uint64_t last_id = 0;

 private:
  template <class C>
  uint64_t record(std::vector<C>& into, const C& c) {
    if (refuse) return 0;
    into.push_back(c);
    return ++last_id;
  }
};

}  // namespace slam::viewer
