#pragma once
// The map viewport (window coordinates, y down) as a GL viewport in framebuffer pixels (y up).
#include <cmath>

#include "viewer/core/view_transform.hpp"
#include "viewer/gl/gl_api.hpp"

namespace slam::viewer {

struct PixelRect {
  int x = 0, y = 0, width = 1, height = 1;  // GL convention: (x, y) is the lower-left corner
};

inline PixelRect to_pixels(const Viewport& vp, double fb_scale, int fb_height) {
  const int x = static_cast<int>(std::lround(vp.x * fb_scale));
  const int w = static_cast<int>(std::lround(vp.width * fb_scale));
  const int h = static_cast<int>(std::lround(vp.height * fb_scale));
  const int top = static_cast<int>(std::lround(vp.y * fb_scale));
  return {x, fb_height - top - h, w < 1 ? 1 : w, h < 1 ? 1 : h};
}

inline void set_gl_viewport(const PixelRect& r) {
  glViewport(r.x, r.y, r.width, r.height);
}

}  // namespace slam::viewer
