// Incremental point buffers and the accumulation texture (see point_layer.hpp).
#include "viewer/gl/point_layer.hpp"

#include <algorithm>

namespace slam::viewer {
namespace {

constexpr size_t kBytesPerPoint = 2 * sizeof(float);
constexpr size_t kInitialCapacity = 4096;

constexpr const char* kPointVertex = R"(#version 330 core
layout(location = 0) in vec2 a_pos;
uniform mat3 u_world_to_ndc;
uniform float u_size;
void main() {
  gl_Position = vec4((u_world_to_ndc * vec3(a_pos, 1.0)).xy, 0.0, 1.0);
  gl_PointSize = u_size;
})";

// Round points when they are big enough for the shape to show; tiny ones stay squares (cheaper).
constexpr const char* kPointFragment = R"(#version 330 core
uniform vec4 u_color;
uniform bool u_round;
out vec4 o_color;
void main() {
  if (u_round) {
    vec2 d = gl_PointCoord * 2.0 - 1.0;
    if (dot(d, d) > 1.0) discard;
  }
  o_color = u_color;
})";

// The accumulation texture as a quad: its own clip space mapped by u_delta to the current one.
constexpr const char* kBlitVertex = R"(#version 330 core
uniform mat3 u_delta;
out vec2 v_uv;
void main() {
  vec2 c = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));
  v_uv = c;
  gl_Position = vec4((u_delta * vec3(c * 2.0 - 1.0, 1.0)).xy, 0.0, 1.0);
})";

constexpr const char* kBlitFragment = R"(#version 330 core
uniform sampler2D u_texture;
in vec2 v_uv;
out vec4 o_color;
void main() { o_color = texture(u_texture, v_uv); })";

bool accumulated(const RobotSettings& s) {
  return s.visible && s.last_n == 0;
}

}  // namespace

Status PointLayer::init(const PacerConfig& pacing) {
  pacer_ = PointPacer(pacing);
  auto p = GlProgram::build("points", kPointVertex, kPointFragment);
  if (!p) return p.error();
  points_ = std::move(*p);
  auto b = GlProgram::build("point texture", kBlitVertex, kBlitFragment);
  if (!b) return b.error();
  blit_ = std::move(*b);
  glGenVertexArrays(1, &blit_vao_);
  return {};
}

PointLayer::~PointLayer() {
  for (auto& b : buffers_) {
    if (b.vbo) glDeleteBuffers(1, &b.vbo);
    if (b.vao) glDeleteVertexArrays(1, &b.vao);
  }
  for (auto& t : targets_) {
    if (t.fbo) glDeleteFramebuffers(1, &t.fbo);
    if (t.texture) glDeleteTextures(1, &t.texture);
  }
  if (blit_vao_) glDeleteVertexArrays(1, &blit_vao_);
}

void PointLayer::grow(RobotBuffer& b, size_t points) {
  if (b.capacity >= points) return;
  size_t cap = std::max(kInitialCapacity, b.capacity);
  while (cap < points) cap *= 2;
  GLuint vbo = 0;
  glGenBuffers(1, &vbo);
  glBindBuffer(GL_COPY_WRITE_BUFFER, vbo);
  glBufferData(GL_COPY_WRITE_BUFFER, static_cast<GLsizeiptr>(cap * kBytesPerPoint), nullptr, GL_DYNAMIC_DRAW);
  if (b.vbo) {
    // Keep what is already on the GPU: a GPU-side copy, never a re-upload from the CPU.
    glBindBuffer(GL_COPY_READ_BUFFER, b.vbo);
    glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0, 0,
                        static_cast<GLsizeiptr>(b.uploaded * kBytesPerPoint));
    glDeleteBuffers(1, &b.vbo);
  }
  stats_.gpu_bytes += (cap - b.capacity) * kBytesPerPoint;
  b.vbo = vbo;
  b.capacity = cap;
  if (!b.vao) glGenVertexArrays(1, &b.vao);
  glBindVertexArray(b.vao);
  glBindBuffer(GL_ARRAY_BUFFER, b.vbo);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, static_cast<GLsizei>(kBytesPerPoint), nullptr);
  glEnableVertexAttribArray(0);
  glBindVertexArray(0);
}

void PointLayer::sync(const RobotRegistry& robots) {
  if (robots.removals() != removals_) {
    // A forgotten robot moved the ones after it: every buffer is uploaded again from its robot.
    removals_ = robots.removals();
    for (RobotBuffer& b : buffers_) b.uploaded = 0;
    ++epoch_;
  }
  if (buffers_.size() < robots.size()) buffers_.resize(robots.size());
  for (size_t i = 0; i < robots.size(); ++i) {
    const PointStore& store = robots.at(i).points;
    RobotBuffer& b = buffers_[i];
    if (b.generation != store.generation()) {
      b.generation = store.generation();
      b.uploaded = 0;
      ++epoch_;
    }
    const size_t n = store.size();
    if (n <= b.uploaded) continue;
    grow(b, n);
    glBindBuffer(GL_ARRAY_BUFFER, b.vbo);
    glBufferSubData(GL_ARRAY_BUFFER, static_cast<GLintptr>(b.uploaded * kBytesPerPoint),
                    static_cast<GLsizeiptr>((n - b.uploaded) * kBytesPerPoint),
                    store.data() + 2 * b.uploaded);
    b.uploaded = n;
  }
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void PointLayer::fingerprint(const RobotRegistry& robots, std::vector<float>& out) const {
  out.clear();
  for (size_t i = 0; i < robots.size(); ++i) {
    const RobotSettings& s = robots.at(i).settings;
    if (!accumulated(s)) {
      out.push_back(-1.0f);
      continue;
    }
    out.insert(out.end(), {s.color.r, s.color.g, s.color.b, s.color.a, s.point_radius_px});
  }
}

bool PointLayer::current(const Target& t, const ViewTransform& view, const std::vector<float>& fp,
                         const PixelRect& px) const {
  return t.valid && t.epoch == epoch_ && t.width == px.width && t.height == px.height && t.view == view &&
         t.fingerprint == fp;
}

void PointLayer::reset(Target& t, const ViewTransform& view, const std::vector<float>& fp,
                       const PixelRect& px) {
  if (!t.fbo || t.width != px.width || t.height != px.height) {
    if (!t.fbo) {
      glGenFramebuffers(1, &t.fbo);
      glGenTextures(1, &t.texture);
    }
    stats_.gpu_bytes -= static_cast<size_t>(t.width) * static_cast<size_t>(t.height) * 4;
    glBindTexture(GL_TEXTURE_2D, t.texture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, px.width, px.height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindFramebuffer(GL_FRAMEBUFFER, t.fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, t.texture, 0);
    t.width = px.width;
    t.height = px.height;
    stats_.gpu_bytes += static_cast<size_t>(t.width) * static_cast<size_t>(t.height) * 4;
  }
  glBindFramebuffer(GL_FRAMEBUFFER, t.fbo);
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  t.valid = true;
  t.epoch = epoch_;
  t.view = view;
  t.fingerprint = fp;
  t.drawn.assign(t.drawn.size(), 0);
}

void PointLayer::draw_range(const RobotBuffer& b, const RobotView& r, size_t first, size_t count,
                            const Affine2& world_to_ndc, double fb_scale) {
  const RobotSettings& s = r.settings;
  float m[9];
  world_to_ndc.to_mat3(m);
  const float size = std::max(1.0f, 2.0f * s.point_radius_px * static_cast<float>(fb_scale));
  glUniformMatrix3fv(points_.uniform("u_world_to_ndc"), 1, GL_FALSE, m);
  glUniform1f(points_.uniform("u_size"), size);
  glUniform1i(points_.uniform("u_round"), size >= 3.0f ? 1 : 0);
  glUniform4f(points_.uniform("u_color"), s.color.r, s.color.g, s.color.b, s.color.a);
  glBindVertexArray(b.vao);
  glDrawArrays(GL_POINTS, static_cast<GLint>(first), static_cast<GLsizei>(count));
  stats_.points_drawn += count;
}

bool PointLayer::advance(Target& t, const RobotRegistry& robots, double fb_scale) {
  uint64_t budget = stats_.step_budget;
  if (t.drawn.size() < robots.size()) t.drawn.resize(robots.size(), 0);
  const Affine2 world_to_ndc = t.view.world_to_ndc();
  bool complete = true;
  bool bound = false;
  for (size_t i = 0; i < robots.size(); ++i) {
    const RobotSettings& s = robots.at(i).settings;
    if (!accumulated(s) || i >= buffers_.size()) continue;
    const size_t end = buffers_[i].uploaded;
    const size_t n = static_cast<size_t>(std::min<uint64_t>(end - t.drawn[i], budget));
    if (n > 0) {
      if (!bound) {
        glBindFramebuffer(GL_FRAMEBUFFER, t.fbo);
        glViewport(0, 0, t.width, t.height);
        // Premultiplied alpha in the texture, so drawing it later composites exactly once.
        glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
        bound = true;
      }
      draw_range(buffers_[i], robots.at(i), t.drawn[i], n, world_to_ndc, fb_scale);
      t.drawn[i] += n;
      budget -= n;
    }
    if (t.drawn[i] < end) complete = false;
  }
  const uint64_t added = stats_.step_budget - budget;
  stats_.points_accumulated += added;
  texture_points_this_frame_ += added;
  if (bound) glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return complete;
}

void PointLayer::show(const Target& t, const Affine2& delta) {
  float m[9];
  delta.to_mat3(m);
  glUseProgram(blit_.id());
  glUniformMatrix3fv(blit_.uniform("u_delta"), 1, GL_FALSE, m);
  glUniform1i(blit_.uniform("u_texture"), 0);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, t.texture);
  glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glBindVertexArray(blit_vao_);
  glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
  glBindVertexArray(0);
}

void PointLayer::end_frame(double frame_ms) {
  pacer_.record(texture_points_this_frame_, frame_ms);
  texture_points_this_frame_ = 0;
}

void PointLayer::draw(const ViewTransform& view, const PixelRect& px, const RobotRegistry& robots,
                      double fb_scale) {
  stats_.points_drawn = 0;
  stats_.points_accumulated = 0;
  stats_.step_budget = pacer_.budget();
  fingerprint(robots, fp_scratch_);
  const bool moving = !have_last_view_ || last_view_ != view;
  have_last_view_ = true;
  last_view_ = view;

  glEnable(GL_BLEND);
  glEnable(GL_PROGRAM_POINT_SIZE);
  glUseProgram(points_.id());
  Target& shown = targets_[shown_];
  Target& work = targets_[1 - shown_];
  const Target* display = nullptr;
  bool complete = false;
  if (current(shown, view, fp_scratch_, px)) {
    // Usually just the points that arrived since the last frame (or the rest of a first fill).
    complete = advance(shown, robots, fb_scale);
    display = &shown;
  } else if (!moving || !shown.valid) {
    // The view holds still (or nothing was ever shown): render a fresh texture, budget-limited.
    if (!current(work, view, fp_scratch_, px)) reset(work, view, fp_scratch_, px);
    complete = advance(work, robots, fb_scale);
    if (complete || !shown.valid) {
      shown_ = 1 - shown_;
      display = &work;
    } else {
      display = &shown;
    }
  } else {
    display = &shown;  // moving: re-project the last finished texture
  }
  stats_.settled = complete && display->valid && current(*display, view, fp_scratch_, px);

  set_gl_viewport(px);
  if (display->valid) {
    const Affine2 delta = display->view.world_to_ndc().inverse().then(view.world_to_ndc());
    show(*display, delta);
  }

  // Robots limited to their last N points: bounded, drawn directly every frame.
  glUseProgram(points_.id());
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  const Affine2 world_to_ndc = view.world_to_ndc();
  for (size_t i = 0; i < robots.size() && i < buffers_.size(); ++i) {
    const RobotSettings& s = robots.at(i).settings;
    if (!s.visible || s.last_n == 0 || buffers_[i].uploaded == 0) continue;
    const size_t n = std::min<size_t>(s.last_n, buffers_[i].uploaded);
    draw_range(buffers_[i], robots.at(i), buffers_[i].uploaded - n, n, world_to_ndc, fb_scale);
  }
  glBindVertexArray(0);
}

}  // namespace slam::viewer
