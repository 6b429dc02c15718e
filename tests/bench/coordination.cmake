# eval_coordination: the whole system with simulated robots sent to random reachable places, with
# the planner's fleet coordination on or off: robot-robot contacts, the longest wait, targets reached
# per minute (include() from tests/bench/CMakeLists.txt; figures in docs/performance.md).
# Run: build/bin/eval_coordination --world maze --robots 10 --duration 1200 --coordination on
add_executable(eval_coordination ${CMAKE_CURRENT_LIST_DIR}/eval_coordination.cpp)
target_link_libraries(eval_coordination PRIVATE simulator_core slam_fastdds slam_testkit nlohmann_json::nlohmann_json)
add_dependencies(eval_coordination slam-gateway slam-mapper slam-planner slam-simulator)
slam_warnings(eval_coordination)
