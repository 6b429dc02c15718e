// View transforms: screen <-> world with pan, zoom, rotation and flip; round trips; fit; the
// log line a test uses to reproduce the viewer's transform.
#include "viewer/core/view_transform.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace slam::viewer {
namespace {

constexpr double kEps = 1e-9;

ViewTransform make_view() {
  ViewTransform v;
  v.set_viewport({100.0, 0.0, 800.0, 600.0});
  v.set({2.0, 3.0}, 40.0, 0.0, false);
  return v;
}

void expect_near(Vec2 a, Vec2 b, double eps = kEps) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
}

TEST(ViewTransform, CentreOfViewportShowsCentreAndYPointsUp) {
  const ViewTransform v = make_view();
  expect_near(v.world_to_screen({2.0, 3.0}), {500.0, 300.0});
  expect_near(v.world_to_screen({3.0, 3.0}), {540.0, 300.0});
  expect_near(v.world_to_screen({2.0, 4.0}), {500.0, 260.0});  // +y up: smaller screen y
}

TEST(ViewTransform, FlipMakesYPointDown) {
  ViewTransform v = make_view();
  v.set_flip_y(true);
  expect_near(v.world_to_screen({2.0, 4.0}), {500.0, 340.0});
  expect_near(v.world_to_screen({2.0, 3.0}), {500.0, 300.0});
}

TEST(ViewTransform, RotationTurnsMapCounterClockwise) {
  ViewTransform v = make_view();
  v.rotate_about({500.0, 300.0}, M_PI / 2.0);
  // +x of the map now points up on screen.
  expect_near(v.world_to_screen({3.0, 3.0}), {500.0, 260.0});
}

TEST(ViewTransform, RoundTripWithPanZoomRotateFlip) {
  ViewTransform v = make_view();
  v.pan_pixels({10.0, 10.0}, {73.0, -41.0});
  v.zoom_about({321.0, 123.0}, 2.7);
  v.rotate_about({600.0, 200.0}, 0.7);
  v.set_flip_y(true);
  for (Vec2 s : {Vec2{0.0, 0.0}, Vec2{100.0, 599.0}, Vec2{899.5, 13.25}})
    expect_near(v.world_to_screen(v.screen_to_world(s)), s, 1e-7);
  for (Vec2 w : {Vec2{-5.0, 2.0}, Vec2{1e3, -1e3}})
    expect_near(v.screen_to_world(v.world_to_screen(w)), w, 1e-7);
}

TEST(ViewTransform, ZoomKeepsPointUnderCursor) {
  ViewTransform v = make_view();
  const Vec2 cursor{217.0, 433.0};
  const Vec2 before = v.screen_to_world(cursor);
  v.zoom_about(cursor, 3.0);
  expect_near(v.screen_to_world(cursor), before);
  EXPECT_DOUBLE_EQ(v.scale(), 120.0);
}

TEST(ViewTransform, PanMovesWorldWithCursor) {
  ViewTransform v = make_view();
  const Vec2 grabbed = v.screen_to_world({300.0, 200.0});
  v.pan_pixels({300.0, 200.0}, {350.0, 180.0});
  expect_near(v.world_to_screen(grabbed), {350.0, 180.0});
}

TEST(ViewTransform, FitShowsWholeBoxWithMargin) {
  ViewTransform v = make_view();
  v.fit({-10.0, -5.0, 10.0, 5.0}, 0.05);
  // 20 m wide into 800 px with 5 % margin each side.
  EXPECT_NEAR(v.scale(), 800.0 / 20.0 / 1.1, 1e-9);
  expect_near(v.world_to_screen({0.0, 0.0}), {500.0, 300.0});
  const Vec2 corner = v.world_to_screen({10.0, 5.0});
  EXPECT_LT(corner.x, 900.0);
  EXPECT_GT(corner.y, 0.0);
}

TEST(ViewTransform, NdcCoversViewport) {
  const ViewTransform v = make_view();
  const Affine2 ndc = v.world_to_ndc();
  expect_near(ndc.apply(v.screen_to_world({100.0, 0.0})), {-1.0, 1.0});
  expect_near(ndc.apply(v.screen_to_world({900.0, 600.0})), {1.0, -1.0});
}

TEST(ViewTransform, DescribeParsesBackExactly) {
  ViewTransform v = make_view();
  v.rotate_about({1.0, 2.0}, 0.3);
  v.zoom_about({5.0, 7.0}, 1.37);
  auto parsed = ViewTransform::parse("2026-01-01 [viewer] [info] " + v.describe());
  ASSERT_TRUE(parsed) << parsed.message();
  EXPECT_TRUE(*parsed == v);
  EXPECT_FALSE(ViewTransform::parse("view center=1,2 scale=x"));
  EXPECT_FALSE(ViewTransform::parse("nothing here"));
}

TEST(Affine2, InverseAndComposition) {
  const Affine2 a{2.0, 0.5, -1.0, 3.0, 4.0, -2.0};
  const Affine2 id = a.then(a.inverse());
  expect_near(id.apply({3.0, -7.0}), {3.0, -7.0});
  float m[9];
  a.to_mat3(m);
  EXPECT_FLOAT_EQ(m[0], 2.0f);
  EXPECT_FLOAT_EQ(m[3], -1.0f);
  EXPECT_FLOAT_EQ(m[6], 4.0f);
  EXPECT_FLOAT_EQ(m[8], 1.0f);
}

}  // namespace
}  // namespace slam::viewer
