// slam-mapper: owns the occupancy grid and every stored observation; publishes snapshots and patches.
// Only wiring: the common service skeleton around MapperNode, or the offline command it names.
#include <iostream>

#include "common/fastdds/run_service.hpp"
#include "mapper/core/mapper_offline.hpp"
#include "mapper/core/mapper_options.hpp"
#include "mapper/dds/domain_claim.hpp"
#include "mapper/dds/mapper_node.hpp"

int main(int argc, char** argv) {
  using namespace slam::mapper;
  MapperOptions options;
  if (auto code = slam::start_service(
          "mapper",
          "slam-mapper: builds the occupancy grid from robot observations, stores them, serves the map", argc,
          argv, options, add_mapper_options))
    return *code;
  if (options.offline()) {
    auto done = run_offline(options);
    if (!done) return slam::exit_error("slam-mapper", done.message());
    std::cout << *done << "\n";
    return slam::kExitOk;
  }
  // One mapper per domain (sole_mapper.hpp): decided before the store is opened.
  auto claim = DomainClaim::take(options.service.domain);
  if (!claim) return slam::exit_error("slam-mapper", claim.message());
  return slam::run_service<MapperNode>("mapper", options, [&claim] { (*claim).reset(); });
}
