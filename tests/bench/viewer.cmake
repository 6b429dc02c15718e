# bench_viewer: frame time of the viewer's renderer with 10 k .. 4 M points, steady, panning and
# appending (included from tests/bench/CMakeLists.txt). Needs a display:
#   xvfb-run -a -s "-screen 0 1280x800x24 -noreset" build/bin/bench_viewer --benchmark_format=json
add_executable(bench_viewer ${CMAKE_CURRENT_LIST_DIR}/bench_viewer.cpp)
target_link_libraries(bench_viewer PRIVATE viewer_gl benchmark::benchmark)
slam_warnings(bench_viewer)
