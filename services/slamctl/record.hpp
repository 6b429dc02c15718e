#pragma once
// `slamctl record` and `slamctl replay`: sessions to and from MCAP files (record.cpp).
#include "slamctl/commands.hpp"

namespace slam::ctl {

Handler add_record(CLI::App& cli);
Handler add_replay(CLI::App& cli);

}  // namespace slam::ctl
