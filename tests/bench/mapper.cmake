# bench_mapper: ray casting, ingest and rebuild-from-store speed of the mapper's grid core
# (include() from tests/bench/CMakeLists.txt). Writes a ~130 MB temporary SQLite file once per run.
# Run: build/bin/bench_mapper --benchmark_format=json
add_executable(bench_mapper ${CMAKE_CURRENT_LIST_DIR}/bench_mapper.cpp)
target_link_libraries(bench_mapper PRIVATE mapper_core slam_testkit benchmark::benchmark)
slam_warnings(bench_mapper)
