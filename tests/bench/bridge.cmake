# bench_bridge: the bridge core's CPU per second of fleet input at 1000 robots x 10 Hz with one
# Foxglove client subscribed to everything (included from tests/bench/CMakeLists.txt).
# Run: build/bin/bench_bridge --benchmark_format=json
add_executable(bench_bridge ${CMAKE_CURRENT_LIST_DIR}/bench_bridge.cpp)
target_link_libraries(bench_bridge PRIVATE bridge_core benchmark::benchmark)
slam_warnings(bench_bridge)
# Smoke run for `ctest -L bench`.
add_test(NAME bench_bridge COMMAND bench_bridge --benchmark_min_time=0.1)
set_tests_properties(bench_bridge PROPERTIES LABELS bench TIMEOUT 300)
