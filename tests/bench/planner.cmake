# bench_planner: A*, OMPL, frontier and re-planning speed on a deterministic 1024x1024 map.
# Included from tests/bench/CMakeLists.txt. Run:
#   bench_planner --benchmark_format=json --benchmark_out=planner.json
add_executable(bench_planner ${CMAKE_CURRENT_LIST_DIR}/bench_planner.cpp)
target_link_libraries(bench_planner PRIVATE planner_core benchmark::benchmark)
slam_warnings(bench_planner)
