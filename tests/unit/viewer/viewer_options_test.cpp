// slam-viewer options: defaults validate, bad values name their flag, --click specs parse.
#include "viewer/core/viewer_options.hpp"

#include <gtest/gtest.h>

namespace slam::viewer {
namespace {

TEST(ViewerOptions, DefaultsAreValid) {
  ViewerOptions o;
  EXPECT_TRUE(validate(o));
  EXPECT_EQ(o.left_action, ClickAction::SetTarget);
}

// Validates options that differ from the defaults by `change`; returns the error (empty if valid).
template <class F>
std::string error_for(F change) {
  ViewerOptions o;
  change(o);
  const Status s = validate(o);
  return s ? std::string{} : s.message();
}

TEST(ViewerOptions, BadValuesNameTheFlag) {
  EXPECT_NE(error_for([](ViewerOptions& o) { o.width = 10; }).find("--width"), std::string::npos);
  EXPECT_NE(error_for([](ViewerOptions& o) { o.right_click = "boom"; }).find("--right-click"),
            std::string::npos);
  EXPECT_NE(error_for([](ViewerOptions& o) { o.tab = "nope"; }).find("--tab"), std::string::npos);
  EXPECT_NE(error_for([](ViewerOptions& o) { o.click_texts = {"1,2,middle@3"}; }).find("--click"),
            std::string::npos);
  EXPECT_NE(error_for([](ViewerOptions& o) { o.frames = 0, o.screenshot = "x.png"; }).find("--frames"),
            std::string::npos);
  EXPECT_NE(error_for([](ViewerOptions& o) { o.snapshot_period_s = 0.0; }).find("--snapshot-period"),
            std::string::npos);
  EXPECT_NE(error_for([](ViewerOptions& o) {
              o.snapshot_dir = "d", o.screenshot = "x.png";
            }).find("--snapshot-dir"),
            std::string::npos);
}

TEST(ViewerOptions, PointPacingComesFromItsFlags) {
  EXPECT_NE(error_for([](ViewerOptions& o) { o.point_frame_ms = 0.5; }).find("--point-frame-ms"),
            std::string::npos);
  EXPECT_NE(error_for([](ViewerOptions& o) { o.point_budget = 10; }).find("--point-budget"),
            std::string::npos);
  ViewerOptions o;
  o.point_budget = 2'000;  // below the pacer's usual minimum and first step: both follow it down
  o.point_frame_ms = 45.0;
  ASSERT_TRUE(validate(o));
  const PacerConfig c = pacer_config(o);
  EXPECT_TRUE(validate(c));
  EXPECT_EQ(c.max_points, 2'000u);
  EXPECT_EQ(c.first_points, 2'000u);
  EXPECT_DOUBLE_EQ(c.frame_ms, 45.0);
  const ViewerOptions defaults;
  EXPECT_TRUE(validate(pacer_config(defaults)));
}

TEST(ViewerOptions, ClickSpecsParse) {
  auto c = parse_click_spec("640.5,400,right@12");
  ASSERT_TRUE(c) << c.message();
  EXPECT_DOUBLE_EQ(c->x, 640.5);
  EXPECT_EQ(c->button, 1);
  EXPECT_EQ(c->frame, 12u);
  EXPECT_FALSE(parse_click_spec("1,2,left"));
  EXPECT_FALSE(parse_click_spec("1,2,left@3junk"));
}

TEST(ViewerOptions, PoseDragSpecsParse) {
  auto d = parse_pose_drag_spec("sim-1:640.5,400>700,380@5-12");
  ASSERT_TRUE(d) << d.message();
  EXPECT_EQ(d->robot, "sim-1");
  EXPECT_DOUBLE_EQ(d->x0, 640.5);
  EXPECT_DOUBLE_EQ(d->y1, 380.0);
  EXPECT_EQ(d->press, 5u);
  EXPECT_EQ(d->release, 12u);
  EXPECT_FALSE(parse_pose_drag_spec("640,400>700,380@5-12"));    // no robot
  EXPECT_FALSE(parse_pose_drag_spec("r:640,400>700,380@12-5"));  // released before pressed
  EXPECT_FALSE(parse_pose_drag_spec("r:640,400>700,380@5-12x"));
  ViewerOptions o;
  o.pose_drag_texts = {"r:1,2>3,4@5"};
  EXPECT_NE(validate(o).message().find("--pose-drag"), std::string::npos);
}

TEST(ViewerOptions, TabNamesResolve) {
  ViewerOptions o;
  o.tab = "mqtt";
  ASSERT_TRUE(validate(o));
  EXPECT_EQ(o.tab_index, 1);
}

}  // namespace
}  // namespace slam::viewer
