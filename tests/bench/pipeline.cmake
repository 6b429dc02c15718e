# bench_pipeline: the whole system under a 1000-robot load (mosquitto -> gateway -> mapper, planner
# running): sustained rate, queue growth, CPU per service, robot-to-map delay (include() from
# tests/bench/CMakeLists.txt). Starts its own mosquitto and every service; takes ~1 minute.
# Run: build/bin/bench_pipeline --benchmark_format=json   (SLAM_BENCH_PIPELINE_SECONDS=N: window)
add_executable(bench_pipeline ${CMAKE_CURRENT_LIST_DIR}/bench_pipeline.cpp ${CMAKE_CURRENT_LIST_DIR}/pipeline_rig.cpp
                              ${CMAKE_CURRENT_LIST_DIR}/pipeline_probe.cpp)
target_link_libraries(bench_pipeline PRIVATE slam_fastdds slam_testkit robot_protocol
                                             slam_testkit_mqtt benchmark::benchmark)
add_dependencies(bench_pipeline slam-gateway slam-mapper slam-planner slam-simulator)
slam_warnings(bench_pipeline)
# Smoke run for `ctest -L bench`: 200 robots for 5 s; the program exits non-zero if the run failed.
add_test(NAME bench_pipeline COMMAND bench_pipeline --benchmark_format=json)
set_tests_properties(bench_pipeline PROPERTIES LABELS bench TIMEOUT 300
                     ENVIRONMENT "SLAM_BENCH_PIPELINE_ROBOTS=200;SLAM_BENCH_PIPELINE_SECONDS=5")
# The Foxglove client for SLAM_BENCH_PIPELINE_BRIDGE=1: websocketpp, built as C++17 like the bridge's
# WebSocket edge (websocketpp 0.8's headers are not valid C++20).
add_library(bench_bridge_client STATIC ${CMAKE_CURRENT_LIST_DIR}/pipeline_bridge_client.cpp)
target_include_directories(bench_bridge_client SYSTEM PRIVATE ${WEBSOCKETPP_INCLUDE_DIR} ${ASIO_INCLUDE_DIR})
target_compile_definitions(bench_bridge_client PRIVATE ASIO_STANDALONE _WEBSOCKETPP_CPP11_STL_)
set_target_properties(bench_bridge_client PROPERTIES CXX_STANDARD 17)
target_link_libraries(bench_bridge_client PUBLIC slam_core PRIVATE nlohmann_json::nlohmann_json Threads::Threads)
slam_warnings(bench_bridge_client)
target_link_libraries(bench_pipeline PRIVATE bench_bridge_client)
add_dependencies(bench_pipeline slam-bridge)
