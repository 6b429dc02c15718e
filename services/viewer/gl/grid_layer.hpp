#pragma once
// The occupancy grid as ONE integer texture (one octet per cell) on the GPU: re-created when the
// layout changes, otherwise updated with glTexSubImage2D over the box patches touched; the
// fragment shader colours cells through the 16-entry palette from cell_colors.hpp.
#include "common/core/result.hpp"
#include "viewer/core/cell_colors.hpp"
#include "viewer/core/grid_mirror.hpp"
#include "viewer/gl/gl_program.hpp"

namespace slam::viewer {

class GridLayer {
 public:
  GridLayer() = default;
  ~GridLayer();
  GridLayer(const GridLayer&) = delete;
  GridLayer& operator=(const GridLayer&) = delete;

  Status init();
  // Brings the texture up to date with `mirror` (uploads only the dirty box).
  void sync(GridMirror& mirror);
  // Draws into the current GL viewport, which must be the map viewport of `view`.
  void draw(const ViewTransform& view, const GridColors& colors, const GridMirror& mirror);

  uint64_t uploaded_cells() const { return uploaded_cells_; }
  const std::string& error() const { return error_; }

 private:
  GlProgram program_;
  GLuint vao_ = 0;
  GLuint texture_ = 0;
  GLint max_texture_size_ = 0;
  uint32_t tex_width_ = 0, tex_height_ = 0;
  uint64_t uploaded_cells_ = 0;
  std::string error_;  // why the grid cannot be shown (too large for this GPU), empty when fine
};

}  // namespace slam::viewer
