// slam-planner: path requests, per-robot goals, waypoint streams and exploration over DDS.
// Only wiring: the common service skeleton around PlannerNode.
#include "common/fastdds/run_service.hpp"
#include "planner/core/planner_options.hpp"
#include "planner/dds/planner_node.hpp"

int main(int argc, char** argv) {
  using namespace slam::planner;
  PlannerOptions options;
  if (auto code = slam::start_service(
          "planner", "slam-planner: answers path requests, drives each robot's standing goal, explores", argc,
          argv, options, add_planner_options))
    return *code;
  return slam::run_service<PlannerNode>("planner", options);
}
