# eval_coordination: the whole system with simulated robots sent to random reachable places, with
# the planner's fleet coordination on or off: robot-robot contacts, the longest wait, targets reached
# per minute (include() from tests/bench/CMakeLists.txt; figures in docs/performance.md).
# Run: build/bin/eval_coordination --world maze --robots 10 --duration 1200 --coordination on

# What both evaluations need of a world: places to send robots to, its walls as a planner grid.
add_library(coordination_eval STATIC ${CMAKE_CURRENT_LIST_DIR}/eval/world_places.cpp)
target_include_directories(coordination_eval PUBLIC ${CMAKE_CURRENT_LIST_DIR})
target_link_libraries(coordination_eval PUBLIC simulator_core planner_core)
slam_warnings(coordination_eval)
add_executable(eval_coordination ${CMAKE_CURRENT_LIST_DIR}/eval_coordination.cpp)
target_link_libraries(eval_coordination PRIVATE coordination_eval slam_fastdds slam_testkit nlohmann_json::nlohmann_json)
add_dependencies(eval_coordination slam-gateway slam-mapper slam-planner slam-simulator)
slam_warnings(eval_coordination)

# eval_traffic: the same rules without the processes (the simulator's robot model and the planner's
# Fleet and FleetCoordinator in one loop): seconds per run, for comparing rule changes over seeds.
# Run: build/bin/eval_traffic --world maze --robots 10 --seeds 8
add_executable(eval_traffic ${CMAKE_CURRENT_LIST_DIR}/eval_traffic.cpp)
target_link_libraries(eval_traffic PRIVATE coordination_eval)
slam_warnings(eval_traffic)
