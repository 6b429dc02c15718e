# bench_slam_graph: optimising a fleet-sized pose graph (10 000 nodes) from a drifted start
# (include() from tests/bench/CMakeLists.txt). Run: build/bin/bench_slam_graph --benchmark_format=json
add_executable(bench_slam_graph ${CMAKE_CURRENT_LIST_DIR}/bench_slam_graph.cpp)
target_link_libraries(bench_slam_graph PRIVATE slam_pose_correction benchmark::benchmark_main)
slam_warnings(bench_slam_graph)
# Smoke run for `ctest -L bench`: one solve of the full graph is short enough.
add_test(NAME bench_slam_graph COMMAND bench_slam_graph --benchmark_format=json)
set_tests_properties(bench_slam_graph PROPERTIES LABELS bench TIMEOUT 300)
