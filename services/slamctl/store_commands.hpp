#pragma once
// slamctl store stats: what the mapper's observation store keeps (read from the SQLite file, beside a
// running mapper: WAL lets it read while the mapper writes).
#include <string>

#include "mapper/core/observation_store.hpp"
#include "slamctl/commands.hpp"

namespace slam::ctl {

Handler add_store(CLI::App& cli);

// The report `store stats` prints (testable without a file).
std::string describe_store(const std::string& path, const mapper::StoreStats& stats);

}  // namespace slam::ctl
