# bench_gateway: broker baseline, MQTT -> gateway -> DDS throughput and latency, gateway memory
# (include() from tests/bench/CMakeLists.txt). Starts its own mosquitto and slam-gateway.
# Run: build/bin/bench_gateway --benchmark_format=json   (SLAM_BENCH_GATEWAY_MESSAGES=N to shorten)
add_executable(bench_gateway ${CMAKE_CURRENT_LIST_DIR}/bench_gateway.cpp)
target_link_libraries(bench_gateway PRIVATE slam_fastdds slam_testkit eclipse-paho-mqtt-c::paho-mqtt3a
                                            benchmark::benchmark)
target_compile_definitions(bench_gateway PRIVATE SLAM_GATEWAY_BIN="$<TARGET_FILE:slam-gateway>")
add_dependencies(bench_gateway slam-gateway)
slam_warnings(bench_gateway)
# Smoke run for `ctest -L bench`: a short message count, same code path.
add_test(NAME bench_gateway COMMAND bench_gateway --benchmark_format=json)
set_tests_properties(bench_gateway PROPERTIES LABELS bench TIMEOUT 300
                     ENVIRONMENT SLAM_BENCH_GATEWAY_MESSAGES=20000)
