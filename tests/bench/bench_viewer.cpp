// Viewer frame time with many measurement points (target on llvmpipe: steady frames with 1 M
// points <= 33 ms, frames while panning or zooming <= 100 ms, and so are the frames that re-render
// the point texture afterwards). Needs a display: run under
//   xvfb-run -a -s "-screen 0 1280x800x24 -noreset" build/bin/bench_viewer
// Each iteration is one frame (grid texture + points + glFinish), timed manually; p50/p95 are
// reported as counters, GL_RENDERER in the context.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "viewer/gl/gl_window.hpp"
#include "viewer/gl/grid_layer.hpp"
#include "viewer/gl/point_layer.hpp"

namespace {

using namespace slam::viewer;
namespace msg = slam::msg;
using Clock = std::chrono::steady_clock;

constexpr int kWidth = 1280, kHeight = 800;

[[noreturn]] void die(const std::string& what) {
  std::fprintf(stderr, "bench_viewer: %s\n", what.c_str());
  std::exit(1);
}

// One window, a 1024² grid and four robots sharing `points` points spread over a 40 m square,
// sorted along x in 1 m strips as a robot's scans roughly are.
struct Scene {
  std::unique_ptr<GlWindow> window;
  GridMirror grid;
  GridColors colors;
  RobotRegistry robots;
  GridLayer grid_layer;
  PointLayer point_layer;
  ViewTransform view;
  PixelRect px{0, 0, kWidth, kHeight};

  // `pacing`: the viewer's defaults unless a benchmark compares another step sizing.
  explicit Scene(size_t points, const PacerConfig& pacing = PacerConfig{}) {
    auto w = GlWindow::create("bench_viewer", kWidth, kHeight);
    if (!w) die(w.message());
    window = std::move(*w);
    if (auto s = grid_layer.init(); !s) die(s.message());
    if (auto s = point_layer.init(pacing); !s) die(s.message());
    msg::GridSnapshot snap{
        1, 1, 0, {1024, 1024, 0.05, {-25.6, -25.6}, 0.2}, std::vector<uint8_t>(1024 * 1024)};
    std::mt19937 rng(7);
    for (auto& c : snap.cells) c = static_cast<uint8_t>(rng() % 3);
    if (auto s = grid.apply_snapshot(std::move(snap)); !s) die(s.message());
    std::uniform_real_distribution<float> u(-20.0f, 20.0f);
    for (int r = 0; r < 4; ++r) {
      std::vector<float> xy(points / 4 * 2);
      for (auto& v : xy) v = u(rng);
      RobotView& robot = robots.get_or_add("robot" + std::to_string(r));
      robot.points.append(xy.data(), xy.size() / 2);
    }
    view.set_viewport({0.0, 0.0, kWidth, kHeight});
    view.fit(grid.bounds());
  }

  double frame_ms() {
    const auto t0 = Clock::now();
    glViewport(0, 0, kWidth, kHeight);
    glClearColor(0.1f, 0.1f, 0.1f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    grid_layer.sync(grid);
    grid_layer.draw(view, colors, grid);
    point_layer.sync(robots);
    point_layer.draw(view, px, robots, 1.0);
    glFinish();
    glfwSwapBuffers(window->handle());
    const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    point_layer.end_frame(ms);
    return ms;
  }

  // Frames until the accumulation texture matches the view; returns their total time.
  double settle_ms() {
    double total = 0.0;
    for (int i = 0; i < 1000; ++i) {
      total += frame_ms();
      if (point_layer.stats().settled) return total;
    }
    die("the point texture never settled");
  }
};

void report(benchmark::State& state, std::vector<double>& ms) {
  std::sort(ms.begin(), ms.end());
  state.counters["p50_ms"] = ms[ms.size() / 2];
  state.counters["p95_ms"] = ms[std::min(ms.size() - 1, ms.size() * 95 / 100)];
  state.counters["points"] = static_cast<double>(state.range(0));
}

// Nothing moves: the texture is drawn, no point is rasterised.
void BM_SteadyFrame(benchmark::State& state) {
  Scene scene(static_cast<size_t>(state.range(0)));
  state.counters["first_settle_ms"] = scene.settle_ms();
  std::vector<double> ms;
  for (auto _ : state) {
    ms.push_back(scene.frame_ms());
    state.SetIterationTime(ms.back() / 1000.0);
  }
  report(state, ms);
}

// The view pans 4 px every frame: the last texture is re-projected.
void BM_PanFrame(benchmark::State& state) {
  Scene scene(static_cast<size_t>(state.range(0)));
  scene.settle_ms();
  std::vector<double> ms;
  double x = 300.0;
  for (auto _ : state) {
    scene.view.pan_pixels({x, 400.0}, {x + 4.0, 400.0});
    x += 4.0;
    ms.push_back(scene.frame_ms());
    state.SetIterationTime(ms.back() / 1000.0);
  }
  // After the pan stops: frames until the texture is re-rendered (steps sized by PointPacer).
  state.counters["resettle_ms"] = scene.settle_ms();
  report(state, ms);
}

// The frames the operator sees after a pan while robots stream (2,000 new points per frame):
// the texture is re-rendered in steps until it matches the view again. Each iteration is one such
// re-render (pan 40 px, then frames until settled); its time is the whole re-render. The counters
// are over every re-render frame: p50/p95/max_frame_ms (each must stay <= 100 ms), and steps (frames
// per re-render). Second argument: 0 sizes the steps by frame time (the viewer's default), N > 0
// rasterises a fixed N points per step (the viewer before the steps were paced: 200,000).
void BM_RerenderFrame(benchmark::State& state) {
  PacerConfig pacing;
  if (state.range(1) > 0) {
    pacing.min_points = pacing.max_points = pacing.first_points = static_cast<uint64_t>(state.range(1));
  }
  Scene scene(static_cast<size_t>(state.range(0)), pacing);
  scene.settle_ms();
  std::vector<float> xy(4000, 1.0f);
  std::vector<double> ms;
  double x = 300.0;
  for (auto _ : state) {
    scene.view.pan_pixels({x, 400.0}, {x + 40.0, 400.0});
    x += 40.0;
    double total = 0.0;
    for (int i = 0;; ++i) {
      if (i == 1000) die("the point texture never settled");
      scene.robots.at(0).points.append(xy.data(), 2000);
      ms.push_back(scene.frame_ms());
      total += ms.back();
      if (scene.point_layer.stats().settled) break;
    }
    state.SetIterationTime(total / 1000.0);
  }
  state.counters["max_frame_ms"] = *std::max_element(ms.begin(), ms.end());
  state.counters["steps"] = static_cast<double>(ms.size()) / static_cast<double>(state.iterations());
  report(state, ms);
}

// Steady view with 2,000 new points per frame (a busy fleet): only those are rasterised.
void BM_AppendFrame(benchmark::State& state) {
  Scene scene(static_cast<size_t>(state.range(0)));
  scene.settle_ms();
  std::vector<float> xy(4000, 1.0f);
  std::vector<double> ms;
  for (auto _ : state) {
    scene.robots.at(0).points.append(xy.data(), 2000);
    ms.push_back(scene.frame_ms());
    state.SetIterationTime(ms.back() / 1000.0);
  }
  report(state, ms);
}

void sizes(benchmark::internal::Benchmark* b) {
  for (int64_t n : {10'000, 100'000, 1'000'000, 4'000'000}) b->Arg(n);
  b->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(60);
}

BENCHMARK(BM_SteadyFrame)->Apply(sizes);
BENCHMARK(BM_PanFrame)->Apply(sizes);
BENCHMARK(BM_AppendFrame)->Apply(sizes);
BENCHMARK(BM_RerenderFrame)
    ->ArgsProduct({{100'000, 1'000'000, 4'000'000}, {0, 200'000}})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(6);

}  // namespace

// The renderer goes into the context (printed and written to the JSON before any benchmark runs),
// so every figure says which GL implementation it was measured on.
int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  {
    auto window = GlWindow::create("bench_viewer", kWidth, kHeight);
    if (!window) die(window.message());
    benchmark::AddCustomContext("GL_RENDERER", (*window)->renderer());
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
