# bench_protocol: per-message cost of the robot protocol codecs. Included from tests/bench/CMakeLists.txt.
# Run: build/bin/bench_protocol --benchmark_min_time=0.2
add_executable(bench_protocol ${CMAKE_CURRENT_LIST_DIR}/bench_protocol.cpp)
target_link_libraries(bench_protocol PRIVATE robot_protocol benchmark::benchmark)
slam_warnings(bench_protocol)
