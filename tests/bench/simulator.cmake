# bench_simulator: fleet tick and beam cast throughput (include() from tests/bench/CMakeLists.txt).
# Run: build/tests/bench/bench_simulator --benchmark_format=json
add_executable(bench_simulator ${CMAKE_CURRENT_LIST_DIR}/bench_simulator.cpp)
target_link_libraries(bench_simulator PRIVATE simulator_core benchmark::benchmark_main)
slam_warnings(bench_simulator)
