// Partial re-render: after keyframes move, redrawing only their tiles gives the grid a full rebuild
// gives, cell for cell (log-odds, classes, inflation); tiles no moved keyframe touches stay as they
// were; a small move replays a small share of the store; sub-cell moves, moves off the grid and
// keyframes drawn with several corrections are handled as the plan says.
#include "mapper/core/partial_rerender.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <random>
#include <tuple>
#include <utility>
#include <vector>

#include "mapper/core/rebuild.hpp"
#include "mapper_test_data.hpp"
#include "temp_dir.hpp"

namespace slam::mapper {
namespace {

// A corridor 40 m (or longer) x 9 m with pillars every 5 m; robots drive along it and see 4 m around them.
constexpr double kHalfWidth = 4.5;
constexpr double kRange = 4.0;
constexpr int kPerKeyframe = 4;  // observations per keyframe

GridConfig corridor_config(bool legacy = false, double half_length = 20.0) {
  GridConfig c;
  c.resolution = 0.05;
  c.origin_x = -half_length - 2.0;
  c.origin_y = -6.0;
  c.width_m = 2 * half_length + 4.0;
  c.height_m = 12.0;
  c.inflation_radius = 0.15;
  c.max_extent_m = 2 * half_length + 20.0;
  c.legacy_mode = legacy;
  return c;
}

// Distance along (c, s) from (x, y) to the corridor's walls or a pillar (a 0.4 m square every 5 m).
double cast(double x, double y, double c, double s, double half_length) {
  double best = kRange + 1.0;
  const auto wall = [&](double t) {
    if (t > 1e-9 && t < best) best = t;
  };
  if (std::abs(c) > 1e-12) {
    wall((half_length - x) / c);
    wall((-half_length - x) / c);
  }
  if (std::abs(s) > 1e-12) {
    wall((kHalfWidth - y) / s);
    wall((-kHalfWidth - y) / s);
  }
  for (double px = 2.5 - half_length; px < half_length; px += 5.0) {  // slab test against each pillar
    double t0 = 0.0, t1 = best;
    bool hit = true;
    for (const auto& [o, d, lo, hi] : {std::tuple{x, c, px - 0.2, px + 0.2}, std::tuple{y, s, -0.2, 0.2}}) {
      if (std::abs(d) < 1e-12) {
        if (o < lo || o > hi) hit = false;
        continue;
      }
      double a = (lo - o) / d, b = (hi - o) / d;
      if (a > b) std::swap(a, b);
      t0 = std::max(t0, a);
      t1 = std::min(t1, b);
    }
    if (hit && t0 <= t1 && t0 > 1e-9) best = std::min(best, t0);
  }
  return best;
}

struct Fixture {
  testkit::TempDir dir{"partial-rerender"};
  std::optional<ObservationStore> store;
  KeyframeCorrections drawn;  // what the first full rebuild draws with
  std::vector<KeyframeId> keyframes;
  int64_t observations = 0;

  // Two robots with keyframes drive the corridor one way and back; a third without keyframes
  // (keyframe 0, as a store written with SLAM off) drives along it too, unless `without_keyframe`
  // is false. Corrections: a few cm each.
  explicit Fixture(int steps = 160, double half_length = 20.0, bool without_keyframe = true) {
    auto s = ObservationStore::open(dir.path() / "m.db");
    EXPECT_TRUE(s.is_ok()) << s.message();
    store.emplace(std::move(*s));
    std::vector<Vec2> hits, misses;
    for (int i = 0; i < steps; ++i) {
      for (int robot = 0; robot < (without_keyframe ? 3 : 2); ++robot) {
        const double t = static_cast<double>(i) / steps;
        const double track = 2 * half_length - 4.0;
        const double x = robot == 1 ? track / 2 - track * t : -track / 2 + track * t;
        const double y = robot == 0 ? -1.5 + std::sin(7 * t) : (robot == 1 ? 1.8 : 3.0 * std::cos(11 * t));
        const double heading = robot == 1 ? std::numbers::pi : 0.0;
        hits.clear();
        misses.clear();
        for (int b = 0; b < 90; ++b) {
          const double a = heading + 2 * std::numbers::pi * b / 90;
          const double c = std::cos(a), sn = std::sin(a);
          const double r = cast(x, y, c, sn, half_length);
          (r <= kRange ? hits : misses)
              .push_back({x + std::min(r, kRange) * c, y + std::min(r, kRange) * sn});
        }
        const KeyframeId kf = robot == 2 ? 0 : static_cast<KeyframeId>(1 + robot * 1000 + i / kPerKeyframe);
        if (kf != 0 && i % kPerKeyframe == 0) {
          keyframes.push_back(kf);
          drawn.set(kf, Pose{0.01 * static_cast<double>(kf % 3), -0.01 * static_cast<double>(kf % 2),
                             0.001 * static_cast<double>(kf % 5)});
        }
        const ObservationView v{x, y, heading, true, hits, misses};
        constexpr const char* kNames[] = {"r0", "r1", "r2"};
        EXPECT_TRUE(store->append(kNames[robot], static_cast<uint64_t>(i), i, kf, v));
        ++observations;
      }
    }
    EXPECT_TRUE(store->flush());
  }
};

struct Redrawn {
  RerenderDecision decision;
  TileRender render;
};

// Plans and draws a re-render to `wanted`, copies the tiles into `grid` and records it in `index`.
Redrawn redraw(OccupancyGrid& grid, FootprintIndex& index, ObservationStore& store,
               const KeyframeCorrections& wanted, const RerenderOptions& options = {}) {
  Redrawn out;
  out.decision = plan_rerender(index, wanted, grid, options);
  if (out.decision.kind != RerenderDecision::Kind::Partial) return out;
  auto render = render_tiles(out.decision.plan, store);
  EXPECT_TRUE(render.is_ok()) << render.message();
  if (!render) return out;
  EXPECT_FALSE(render->outside_grid);
  grid.redraw(render->canvas);
  record_redraw(*render, index);
  out.render = std::move(*render);
  return out;
}

OccupancyGrid full_rebuild(const GridConfig& config, ObservationStore& store, const KeyframeCorrections& c,
                           FootprintIndex* index = nullptr, RebuildStats* stats = nullptr) {
  auto grid = rebuild_grid(config, store, stats, c, index);
  EXPECT_TRUE(grid.is_ok()) << grid.message();
  return std::move(*grid);
}

// Moves keyframe `kf` by (dx, dy, dtheta) on top of its current correction.
void move(KeyframeCorrections& c, KeyframeId kf, double dx, double dy, double dtheta) {
  const Pose p = c.lookup(kf);
  c.set(kf, Pose{p.x + dx, p.y + dy, p.theta + dtheta});
}

class PartialRerender : public ::testing::TestWithParam<bool> {};  // legacy mode or not

TEST_P(PartialRerender, EqualsAFullRebuildCellForCell) {
  Fixture f;
  const GridConfig config = corridor_config(GetParam());
  FootprintIndex index;
  RebuildStats full_stats;
  OccupancyGrid grid = full_rebuild(config, *f.store, f.drawn, &index, &full_stats);
  EXPECT_EQ(full_stats.observations, f.observations);
  EXPECT_EQ(index.observations(), f.observations);

  // A loop closure moves a stretch of robot 0's keyframes, then a second one moves one of robot 1's
  // back and turns it; each time the partial grid equals a full rebuild with the same corrections.
  KeyframeCorrections wanted = f.drawn;
  for (KeyframeId kf = 12; kf <= 15; ++kf) move(wanted, kf, 0.12, -0.07, 0.01);
  Redrawn first = redraw(grid, index, *f.store, wanted);
  ASSERT_EQ(first.decision.kind, RerenderDecision::Kind::Partial) << first.decision.reason;
  EXPECT_EQ(first.decision.plan.moved, 4u);
  test_data::expect_same(grid, full_rebuild(config, *f.store, wanted));

  move(wanted, 1020, -0.3, 0.2, -0.05);
  move(wanted, 13, -0.12, 0.07, -0.01);  // back where it was
  Redrawn second = redraw(grid, index, *f.store, wanted);
  ASSERT_EQ(second.decision.kind, RerenderDecision::Kind::Partial) << second.decision.reason;
  EXPECT_EQ(second.decision.plan.moved, 2u);
  test_data::expect_same(grid, full_rebuild(config, *f.store, wanted));
}

TEST_P(PartialRerender, WithAPriorEqualsAFullRebuild) {
  Fixture f(80);
  const GridConfig config = corridor_config(GetParam());
  MapImage prior;  // a drawn map of the west half: free inside, a wall at y = 2
  prior.width = 200;
  prior.height = 120;
  prior.resolution = 0.1;
  prior.origin_x = -20.0;
  prior.origin_y = -4.0;
  prior.cells.assign(size_t{prior.width} * prior.height, kMapFree);
  for (uint32_t u = 0; u < prior.width; ++u) prior.cells[60 * size_t{prior.width} + u] = kMapOccupied;
  ASSERT_TRUE(f.store->save_prior(prior));
  FootprintIndex index;
  OccupancyGrid grid = full_rebuild(config, *f.store, f.drawn, &index);
  KeyframeCorrections wanted = f.drawn;
  move(wanted, 5, 0.0, 0.25, 0.02);
  const Redrawn r = redraw(grid, index, *f.store, wanted);
  ASSERT_EQ(r.decision.kind, RerenderDecision::Kind::Partial) << r.decision.reason;
  test_data::expect_same(grid, full_rebuild(config, *f.store, wanted));
}

INSTANTIATE_TEST_SUITE_P(Modes, PartialRerender, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& p) { return p.param ? "Legacy" : "Rays"; });

// The corrections every observation is drawn with, as the index says (keyframe-0 runs: identity).
KeyframeCorrections drawn_corrections(const FootprintIndex& index) {
  KeyframeCorrections c;
  for (const FootprintGroup& g : index.groups())
    if (g.keyframe != 0) c.set(g.keyframe, g.drawn);
  return c;
}

TEST(PartialRerenderRandom, AnySequenceOfClosuresEqualsAFullRebuildOfWhatIsDrawn) {
  // Rounds of random moves, some under a quarter cell (not redrawn: they add up), some of decimetres
  // and a few degrees; after each, the grid equals a full rebuild with the corrections it is drawn
  // with, and those are the wanted ones wherever a keyframe moved by more than a quarter cell.
  Fixture f(120);
  const GridConfig config = corridor_config();
  FootprintIndex index;
  OccupancyGrid grid = full_rebuild(config, *f.store, f.drawn, &index);
  KeyframeCorrections wanted = f.drawn;
  std::mt19937 rng(5);
  std::uniform_int_distribution<size_t> pick(0, f.keyframes.size() - 1);
  std::uniform_real_distribution<double> small(-0.004, 0.004), large(-0.25, 0.25), turn(-0.04, 0.04);
  int partial = 0;
  for (int round = 0; round < 8; ++round) {
    const int moves = 1 + round % 4;
    for (int m = 0; m < moves; ++m) {
      const KeyframeId kf = f.keyframes[pick(rng)];
      if (m % 2 == 0)
        move(wanted, kf, large(rng), large(rng) * 0.5, turn(rng));
      else
        move(wanted, kf, small(rng), small(rng), 0.0);
    }
    const Redrawn r = redraw(grid, index, *f.store, wanted);
    if (r.decision.kind == RerenderDecision::Kind::Full) {  // as the mapper does
      grid = full_rebuild(config, *f.store, wanted, &index);
      continue;
    }
    partial += r.decision.kind == RerenderDecision::Kind::Partial ? 1 : 0;
    test_data::expect_same(grid, full_rebuild(config, *f.store, drawn_corrections(index)));
    const double quarter = 0.25 * config.resolution;
    for (const FootprintGroup& g : index.groups()) {
      if (g.keyframe == 0) continue;
      const Pose w = wanted.lookup(g.keyframe);
      const Pose delta = w.compose(g.drawn.inverse());
      for (const Vec2 c : {Vec2{g.box.x0, g.box.y0}, Vec2{g.box.x1, g.box.y1}, Vec2{g.box.x0, g.box.y1},
                           Vec2{g.box.x1, g.box.y0}}) {
        const Vec2 m = delta.transform(c);
        EXPECT_LE(std::hypot(m.x - c.x, m.y - c.y), quarter + 1e-9) << "keyframe " << g.keyframe;
      }
    }
  }
  EXPECT_GE(partial, 4);
}

TEST(PartialRerenderTiles, TilesNoMovedKeyframeTouchesStayAsTheyWere) {
  Fixture f;
  const GridConfig config = corridor_config();
  FootprintIndex index;
  OccupancyGrid grid = full_rebuild(config, *f.store, f.drawn, &index);
  const OccupancyGrid before = grid;
  grid.clear_dirty();
  KeyframeCorrections wanted = f.drawn;
  move(wanted, 30, 0.2, 0.1, 0.0);
  const Redrawn r = redraw(grid, index, *f.store, wanted);
  ASSERT_EQ(r.decision.kind, RerenderDecision::Kind::Partial) << r.decision.reason;
  const std::vector<uint32_t>& tiles = r.decision.plan.tiles;
  const TileLayout layout{grid.width(), grid.height(), kGridTileSide};
  EXPECT_LT(tiles.size(), layout.count() / 4);
  int64_t changed_outside = 0;
  for (int32_t y = 0; y < grid.height(); ++y)
    for (int32_t x = 0; x < grid.width(); ++x) {
      if (std::binary_search(tiles.begin(), tiles.end(), layout.tile_of(x, y))) continue;
      if (grid.log_odds(x, y) != before.log_odds(x, y) || grid.cell_class(x, y) != before.cell_class(x, y))
        ++changed_outside;
    }
  EXPECT_EQ(changed_outside, 0);
  // What a patch carries: tiles whose classes changed, within the redrawn ones or their inflation rim.
  int64_t dirty = 0;
  grid.dirty_tiles().for_each([&](uint32_t) { ++dirty; });
  EXPECT_GT(dirty, 0);
  EXPECT_LE(dirty, static_cast<int64_t>(tiles.size()) * 2);
}

TEST(PartialRerenderCost, ASmallMoveReplaysASmallShareOfTheStore) {
  Fixture f(240, 50.0, false);  // 100 m of corridor: a keyframe sees 8 m of it
  const GridConfig config = corridor_config(false, 50.0);
  FootprintIndex index;
  RebuildStats full_stats;
  OccupancyGrid grid = full_rebuild(config, *f.store, f.drawn, &index, &full_stats);
  KeyframeCorrections wanted = f.drawn;
  move(wanted, 30, 0.1, 0.0, 0.0);
  const Redrawn r = redraw(grid, index, *f.store, wanted);
  ASSERT_EQ(r.decision.kind, RerenderDecision::Kind::Partial) << r.decision.reason;
  EXPECT_GT(r.render.replayed, 0);
  EXPECT_LT(r.render.replayed * 4, full_stats.observations)
      << r.render.replayed << " of " << full_stats.observations << " observations replayed";
  EXPECT_LE(r.render.replayed, r.render.rows_read);
  EXPECT_LT(r.render.rows_read * 3, full_stats.observations);
}

TEST(PartialRerenderPlan, SubCellMovesAreNotRedrawnUntilTheyAddUp) {
  Fixture f(40);
  const GridConfig config = corridor_config();
  FootprintIndex index;
  OccupancyGrid grid = full_rebuild(config, *f.store, f.drawn, &index);
  KeyframeCorrections wanted = f.drawn;
  move(wanted, 3, 0.005, 0.0, 0.0);  // a tenth of a cell
  EXPECT_EQ(plan_rerender(index, wanted, grid, {}).kind, RerenderDecision::Kind::Nothing);
  move(wanted, 3, 0.005, 0.0, 0.0);
  move(wanted, 3, 0.005, 0.0, 0.0);  // three tenths: more than a quarter cell from where it is drawn
  const RerenderDecision d = plan_rerender(index, wanted, grid, {});
  ASSERT_EQ(d.kind, RerenderDecision::Kind::Partial);
  EXPECT_EQ(d.plan.moved, 1u);
  // A turn of 2 mrad about the map origin moves points 7-15 m away by 1.4-3 cm: more than a quarter cell.
  KeyframeCorrections turned = f.drawn;
  move(turned, 3, 0.0, 0.0, 0.002);
  EXPECT_EQ(plan_rerender(index, turned, grid, {}).kind, RerenderDecision::Kind::Partial);
}

TEST(PartialRerenderPlan, LargeOrOffGridMovesAndMixedKeyframesRebuildFully) {
  Fixture f(40);
  const GridConfig config = corridor_config();
  FootprintIndex index;
  OccupancyGrid grid = full_rebuild(config, *f.store, f.drawn, &index);
  KeyframeCorrections off = f.drawn;
  move(off, 3, 0.0, 5.0, 0.0);  // out of the grid's 12 m height
  RerenderDecision d = plan_rerender(index, off, grid, {});
  EXPECT_EQ(d.kind, RerenderDecision::Kind::Full);
  EXPECT_NE(d.reason.find("beyond the grid"), std::string::npos) << d.reason;

  KeyframeCorrections all = f.drawn;
  for (KeyframeId kf : f.keyframes) move(all, kf, 0.2, 0.0, 0.0);
  d = plan_rerender(index, all, grid, {});
  EXPECT_EQ(d.kind, RerenderDecision::Kind::Full);
  EXPECT_NE(d.reason.find("tiles to redraw"), std::string::npos) << d.reason;
  EXPECT_EQ(plan_rerender(index, all, grid, RerenderOptions{0.25, 1.0}).kind,
            RerenderDecision::Kind::Partial);

  FootprintIndex mixed = index;
  mixed.add(3, 1'000'000, Pose{1.0, 0.0, 0.0}, MapBox{});
  d = plan_rerender(mixed, f.drawn, grid, {});
  EXPECT_EQ(d.kind, RerenderDecision::Kind::Full);
  EXPECT_NE(d.reason.find("several corrections"), std::string::npos) << d.reason;
}

TEST(RerenderOptions, Validate) {
  EXPECT_TRUE(validate(RerenderOptions{}));
  EXPECT_NE(validate(RerenderOptions{-1.0, 0.5}).message().find("rerender.min_shift_cells"),
            std::string::npos);
  EXPECT_NE(validate(RerenderOptions{0.25, 1.5}).message().find("rerender.max_tile_fraction"),
            std::string::npos);
}

TEST(FootprintIndex, OneGroupPerKeyframeAndShortRunsWithoutOne) {
  FootprintIndex index;
  const Pose p{0.1, 0.0, 0.0};
  index.add(7, 1, p, box_of(ObservationView{0.0, 0.0, 0.0, false, {}, {}}));
  const std::vector<Vec2> far{{3.0, -1.0}};
  index.add(7, 4, p, box_of(ObservationView{1.0, 1.0, 0.0, false, far, {}}));
  for (int64_t row = 10; row < 10 + FootprintIndex::kStaticRun + 1; ++row)
    index.add(0, row, Pose{}, box_of(ObservationView{0.5, 0.5, 0.0, false, {}, {}}));
  ASSERT_EQ(index.groups().size(), 3u);  // keyframe 7, one full run, a run of one
  const FootprintGroup& g = index.groups()[0];
  EXPECT_EQ(g.keyframe, 7u);
  EXPECT_EQ(g.first_row, 1);
  EXPECT_EQ(g.last_row, 4);
  EXPECT_EQ(g.rows, 2);
  EXPECT_EQ(g.box, (MapBox{0.0, -1.0, 3.0, 1.0}));
  EXPECT_EQ(index.groups()[1].rows, FootprintIndex::kStaticRun);
  EXPECT_EQ(index.observations(), 2 + FootprintIndex::kStaticRun + 1);
  index.add(7, 5, Pose{}, MapBox{});  // drawn with another correction: mixed from now on
  EXPECT_FALSE(is_finite(index.groups()[0].drawn));
  index.add(7, 6, p, MapBox{});
  EXPECT_FALSE(is_finite(index.groups()[0].drawn));
  EXPECT_LT(index.memory_bytes(), 4096u);
}

}  // namespace
}  // namespace slam::mapper
