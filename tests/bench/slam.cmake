# bench_slam: speed of the SLAM core (services/pose_correction): keyframe matching against an
# office-sized grid (include() from tests/bench/CMakeLists.txt). Graph benchmarks may add sources.
# Run: build/bin/bench_slam --benchmark_format=json
add_executable(bench_slam ${CMAKE_CURRENT_LIST_DIR}/bench_slam.cpp)
target_link_libraries(bench_slam PRIVATE slam_pose_correction slam_testkit benchmark::benchmark)
slam_warnings(bench_slam)
