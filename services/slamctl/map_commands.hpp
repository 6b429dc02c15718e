#pragma once
// The map's subcommands (map_commands.cpp): map save|load, trajectory, grid, obstruct, unobstruct and
// reset.
#include "slamctl/commands.hpp"

namespace slam::ctl {

Handler add_map(CLI::App& cli);
Handler add_trajectory(CLI::App& cli);
Handler add_grid(CLI::App& cli);
Handler add_obstruct(CLI::App& cli);
Handler add_unobstruct(CLI::App& cli);
Handler add_reset(CLI::App& cli);

}  // namespace slam::ctl
