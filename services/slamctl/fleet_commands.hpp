#pragma once
// The fleet's subcommands (fleet_commands.cpp): status, robots, alerts, forget, goal, mission,
// missions, path and pose.
#include "slamctl/commands.hpp"

namespace slam::ctl {

Handler add_status(CLI::App& cli);
Handler add_robots(CLI::App& cli);
Handler add_alerts(CLI::App& cli);
Handler add_forget(CLI::App& cli);
Handler add_goal(CLI::App& cli);
Handler add_mission(CLI::App& cli);
Handler add_missions(CLI::App& cli);
Handler add_path(CLI::App& cli);
Handler add_pose(CLI::App& cli);
Handler add_placement(CLI::App& cli);

}  // namespace slam::ctl
