# bench_slam: speed of the SLAM core (services/pose_correction): keyframe matching against an
# office-sized grid, and optimising a fleet-sized pose graph (10 000 nodes) from a drifted start
# (include() from tests/bench/CMakeLists.txt). Run: build/bin/bench_slam --benchmark_format=json
add_executable(bench_slam ${CMAKE_CURRENT_LIST_DIR}/bench_slam.cpp ${CMAKE_CURRENT_LIST_DIR}/bench_slam_graph.cpp
                          ${CMAKE_CURRENT_LIST_DIR}/bench_slam_placement.cpp)
target_link_libraries(bench_slam PRIVATE slam_pose_correction slam_testkit benchmark::benchmark)
slam_warnings(bench_slam)

# bench_slam_fleet: the mapper's map loop with pose correction at fleet load (1000 robots x 10 Hz),
# without DDS: CPU of the loop thread and the process, and what correction holds back.
# Run: build/bin/bench_slam_fleet   (SLAM_BENCH_FLEET_ROBOTS, SLAM_BENCH_FLEET_SECONDS)
add_executable(bench_slam_fleet ${CMAKE_CURRENT_LIST_DIR}/bench_slam_fleet.cpp)
target_link_libraries(bench_slam_fleet PRIVATE mapper_core slam_testkit benchmark::benchmark)
slam_warnings(bench_slam_fleet)
