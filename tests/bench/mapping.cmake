# eval_mapping: one run of the whole system (mosquitto, gateway, mapper, planner, simulator) with
# simulated robots exploring a world faster than real time, scored against the simulator's ground
# truth: ATE, goal accuracy, the exported map against the true walls (include() from
# tests/bench/CMakeLists.txt). Not a Google Benchmark: it writes <out>/<name>.json and .png;
# scripts/bench.sh --only mapping runs the matrix and writes docs/mapping-quality.md.
# Run: build/bin/eval_mapping --world office --protocol v1 --speed 8 --duration 1200
# mapping_eval: the metrics and the recorder, plain C++ (unit tests in tests/unit/bench).
add_library(mapping_eval STATIC ${CMAKE_CURRENT_LIST_DIR}/eval/trajectory_metrics.cpp
                                ${CMAKE_CURRENT_LIST_DIR}/eval/waypoint_arrivals.cpp
                                ${CMAKE_CURRENT_LIST_DIR}/eval/map_metrics.cpp
                                ${CMAKE_CURRENT_LIST_DIR}/eval/map_overlay.cpp
                                ${CMAKE_CURRENT_LIST_DIR}/eval/run_recorder.cpp
                                ${CMAKE_CURRENT_LIST_DIR}/eval/closure_audit.cpp
                                ${CMAKE_CURRENT_LIST_DIR}/eval/truth_log.cpp
                                ${CMAKE_CURRENT_LIST_DIR}/eval/run_score.cpp
                                ${CMAKE_CURRENT_LIST_DIR}/eval/relation_metric.cpp)
target_include_directories(mapping_eval PUBLIC ${CMAKE_CURRENT_LIST_DIR})
# simulator_core for its segment geometry, viewer_core for PNG files.
target_link_libraries(mapping_eval PUBLIC slam_core simulator_core viewer_core nlohmann_json::nlohmann_json)
slam_warnings(mapping_eval)

add_executable(eval_mapping ${CMAKE_CURRENT_LIST_DIR}/eval_mapping.cpp ${CMAKE_CURRENT_LIST_DIR}/eval_mapping_tap.cpp)
target_link_libraries(eval_mapping PRIVATE mapping_eval coordination_eval slam_fastdds slam_testkit nlohmann_json::nlohmann_json)
add_dependencies(eval_mapping slam-gateway slam-mapper slam-planner slam-simulator)
slam_warnings(eval_mapping)

# eval_replay: the mapper's map loop with pose correction, offline and deterministic, on a run
# eval_mapping recorded (<out>/<name>.db and .truth), scored the same way.
# Run: build/bin/eval_replay build/bench/mapping/office-v1-drift0.02 --world office
# mapping_replay: the replay loop itself (unit tests in tests/unit/bench).
add_library(mapping_replay STATIC ${CMAKE_CURRENT_LIST_DIR}/eval/replay.cpp
                                  ${CMAKE_CURRENT_LIST_DIR}/eval/log_observations.cpp)
target_link_libraries(mapping_replay PUBLIC mapping_eval mapper_core slam_testkit slam_robot_log)
slam_warnings(mapping_replay)
add_executable(eval_replay ${CMAKE_CURRENT_LIST_DIR}/eval_replay.cpp)
target_link_libraries(eval_replay PRIVATE mapping_replay CLI11::CLI11)
slam_warnings(eval_replay)

# eval_log: a robot's CARMEN log (e.g. the Freiburg SLAM benchmark's) through the same offline loop,
# scored with the benchmark's relation file (final trajectory, published poses, raw odometry).
# Run: build/bin/eval_log intel.clf.gz --beams 16 --max-range 8 (scripts/bench.sh --only logs DIR)
add_executable(eval_log ${CMAKE_CURRENT_LIST_DIR}/eval_log.cpp)
target_link_libraries(eval_log PRIVATE mapping_replay CLI11::CLI11)
slam_warnings(eval_log)
