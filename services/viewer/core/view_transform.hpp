#pragma once
// The map view: where the map frame (metres, +y up) lands in the window (pixels, +y down) after
// pan, zoom, rotation and an optional vertical flip. Pure math so input handling, rendering and
// tests share one definition of "what is under the cursor".
#include <string>

#include "common/core/geometry.hpp"
#include "common/core/result.hpp"

namespace slam::viewer {

// p' = (a*x + c*y + tx, b*x + d*y + ty): a 2D affine map, column-major like GL's mat3.
struct Affine2 {
  double a = 1.0, b = 0.0, c = 0.0, d = 1.0, tx = 0.0, ty = 0.0;

  Vec2 apply(Vec2 p) const { return {a * p.x + c * p.y + tx, b * p.x + d * p.y + ty}; }
  Affine2 then(const Affine2& next) const;  // next ∘ this
  Affine2 inverse() const;
  // Column-major 3x3 floats for glUniformMatrix3fv.
  void to_mat3(float out[9]) const;
};

// A rectangle in window pixels (x, y: top-left corner).
struct Viewport {
  double x = 0.0;
  double y = 0.0;
  double width = 1.0;
  double height = 1.0;
};

struct WorldBox {
  double min_x = 0.0, min_y = 0.0, max_x = 0.0, max_y = 0.0;
};

class ViewTransform {
 public:
  static constexpr double kMinScale = 1e-3;  // pixels per metre
  static constexpr double kMaxScale = 1e5;

  void set_viewport(const Viewport& vp) { viewport_ = vp; }
  const Viewport& viewport() const { return viewport_; }

  Vec2 world_to_screen(Vec2 w) const { return world_to_screen_affine().apply(w); }
  Vec2 screen_to_world(Vec2 s) const { return world_to_screen_affine().inverse().apply(s); }
  Affine2 world_to_screen_affine() const;
  // World to GL clip space of the viewport (x right, y up, -1..1).
  Affine2 world_to_ndc() const;

  // Moves the map by a cursor drag from `from` to `to` (window pixels).
  void pan_pixels(Vec2 from, Vec2 to);
  // Multiplies the scale by `factor`, keeping the world point under `cursor` fixed.
  void zoom_about(Vec2 cursor, double factor);
  // Rotates by `radians` (counter-clockwise on screen) about the window point `pivot`.
  void rotate_about(Vec2 pivot, double radians);
  // Toggles the vertical axis (+y up vs +y down), keeping the viewport centre fixed.
  void set_flip_y(bool flip);
  // Centres `box` in the viewport at the current rotation with `margin` (0.05 = 5 %) around it.
  void fit(const WorldBox& box, double margin = 0.05);

  double scale() const { return scale_; }
  double angle() const { return angle_; }
  bool flip_y() const { return flip_y_; }
  void set(Vec2 center, double scale, double angle, bool flip_y);

  // One line "view center=x,y scale=s angle=a flip=0|1 viewport=x,y,w,h" and its parser, so a
  // test can reproduce the viewer's transform from its log.
  std::string describe() const;
  static Result<ViewTransform> parse(const std::string& line);

  bool operator==(const ViewTransform& o) const;
  bool operator!=(const ViewTransform& o) const { return !(*this == o); }

 private:
  Viewport viewport_;
  Vec2 center_;          // world point at the viewport centre
  double scale_ = 50.0;  // pixels per metre
  double angle_ = 0.0;   // radians, map rotation on screen (counter-clockwise)
  bool flip_y_ = false;  // false: map +y points up on screen
};

}  // namespace slam::viewer
