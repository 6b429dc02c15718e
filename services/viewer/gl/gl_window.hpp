#pragma once
// A GLFW window with an OpenGL 3.3 core context (forward-compatible, as Mesa and macOS want it),
// shared by the viewer and its benchmark; GLFW errors are logged, never thrown.
#include <memory>
#include <string>

#include "common/core/result.hpp"
#include "viewer/core/png_file.hpp"
#include "viewer/gl/gl_api.hpp"

namespace slam::viewer {

class GlWindow {
 public:
  static Result<std::unique_ptr<GlWindow>> create(const std::string& title, int width, int height);
  ~GlWindow();
  GlWindow(const GlWindow&) = delete;
  GlWindow& operator=(const GlWindow&) = delete;

  GLFWwindow* handle() const { return window_; }
  void framebuffer_size(int* w, int* h) const { glfwGetFramebufferSize(window_, w, h); }
  // Framebuffer pixels per window coordinate (1 except on HiDPI screens).
  double framebuffer_scale() const;
  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
  std::string renderer() const;

 private:
  GlWindow() = default;
  GLFWwindow* window_ = nullptr;
};

// The back buffer (w x h, RGB, bottom row first as GL returns it). Cheap next to PNG encoding,
// which is why periodic snapshots only do this on the render thread.
RgbImage read_back_buffer(int width, int height);
// read_back_buffer + write_png: a PNG that appears complete or not at all.
Status write_screenshot(const std::string& path, int width, int height);

}  // namespace slam::viewer
