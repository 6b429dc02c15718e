// Grid texture upload and drawing (see grid_layer.hpp).
#include "viewer/gl/grid_layer.hpp"

#include <string>

namespace slam::viewer {
namespace {

// A quad over the grid's world box, from gl_VertexID alone (no vertex buffer).
constexpr const char* kVertex = R"(#version 330 core
uniform mat3 u_world_to_ndc;
uniform vec4 u_box;
out vec2 v_uv;
void main() {
  vec2 c = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));
  v_uv = c;
  vec2 w = mix(u_box.xy, u_box.zw, c);
  gl_Position = vec4((u_world_to_ndc * vec3(w, 1.0)).xy, 0.0, 1.0);
})";

constexpr const char* kFragment = R"(#version 330 core
uniform usampler2D u_cells;
uniform vec4 u_palette[16];
in vec2 v_uv;
out vec4 o_color;
void main() {
  uint cell = texture(u_cells, v_uv).r;
  o_color = u_palette[cell & 15u];
})";

}  // namespace

Status GridLayer::init() {
  auto p = GlProgram::build("grid", kVertex, kFragment);
  if (!p) return p.error();
  program_ = std::move(*p);
  glGenVertexArrays(1, &vao_);
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_texture_size_);
  return {};
}

GridLayer::~GridLayer() {
  if (texture_) glDeleteTextures(1, &texture_);
  if (vao_) glDeleteVertexArrays(1, &vao_);
}

void GridLayer::sync(GridMirror& mirror) {
  if (!mirror.has_grid()) return;
  const auto& info = mirror.info();
  const bool relayout = mirror.take_layout_changed();
  const CellBox dirty = mirror.take_dirty();
  if (info.width > static_cast<uint32_t>(max_texture_size_) ||
      info.height > static_cast<uint32_t>(max_texture_size_)) {
    error_ = "grid " + std::to_string(info.width) + "x" + std::to_string(info.height) +
             " exceeds this GPU's texture size " + std::to_string(max_texture_size_);
    return;
  }
  error_.clear();
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  if (relayout || !texture_ || tex_width_ != info.width || tex_height_ != info.height) {
    if (!texture_) glGenTextures(1, &texture_);
    glBindTexture(GL_TEXTURE_2D, texture_);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R8UI, static_cast<GLsizei>(info.width),
                 static_cast<GLsizei>(info.height), 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE,
                 mirror.cells().data());
    tex_width_ = info.width;
    tex_height_ = info.height;
    uploaded_cells_ += uint64_t{info.width} * info.height;
    return;
  }
  if (dirty.empty()) return;
  glBindTexture(GL_TEXTURE_2D, texture_);
  // Upload the box straight out of the full-width mirror: no staging copy.
  glPixelStorei(GL_UNPACK_ROW_LENGTH, static_cast<GLint>(info.width));
  glPixelStorei(GL_UNPACK_SKIP_PIXELS, static_cast<GLint>(dirty.x0));
  glPixelStorei(GL_UNPACK_SKIP_ROWS, static_cast<GLint>(dirty.y0));
  glTexSubImage2D(GL_TEXTURE_2D, 0, static_cast<GLint>(dirty.x0), static_cast<GLint>(dirty.y0),
                  static_cast<GLsizei>(dirty.width), static_cast<GLsizei>(dirty.height), GL_RED_INTEGER,
                  GL_UNSIGNED_BYTE, mirror.cells().data());
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  glPixelStorei(GL_UNPACK_SKIP_PIXELS, 0);
  glPixelStorei(GL_UNPACK_SKIP_ROWS, 0);
  uploaded_cells_ += dirty.cells();
}

void GridLayer::draw(const ViewTransform& view, const GridColors& colors, const GridMirror& mirror) {
  if (!texture_ || !error_.empty() || !mirror.has_grid()) return;
  float m[9];
  view.world_to_ndc().to_mat3(m);
  const WorldBox b = mirror.bounds();
  const auto palette = cell_palette(colors);
  float flat[16 * 4];
  for (size_t i = 0; i < palette.size(); ++i) {
    flat[4 * i] = palette[i].r;
    flat[4 * i + 1] = palette[i].g;
    flat[4 * i + 2] = palette[i].b;
    flat[4 * i + 3] = palette[i].a;
  }
  glUseProgram(program_.id());
  glUniformMatrix3fv(program_.uniform("u_world_to_ndc"), 1, GL_FALSE, m);
  glUniform4f(program_.uniform("u_box"), static_cast<float>(b.min_x), static_cast<float>(b.min_y),
              static_cast<float>(b.max_x), static_cast<float>(b.max_y));
  glUniform4fv(program_.uniform("u_palette"), 16, flat);
  glUniform1i(program_.uniform("u_cells"), 0);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, texture_);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glBindVertexArray(vao_);
  glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
  glBindVertexArray(0);
}

}  // namespace slam::viewer
