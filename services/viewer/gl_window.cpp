// GLFW window + GL 3.3 core context, and PNG screenshots of the back buffer (see gl_window.hpp).
#include "viewer/gl_window.hpp"

#include <spdlog/spdlog.h>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

#include <vector>

namespace slam::viewer {
namespace {

void log_glfw_error(int code, const char* description) { spdlog::error("GLFW error {}: {}", code, description); }

}  // namespace

Result<std::unique_ptr<GlWindow>> GlWindow::create(const std::string& title, int width, int height) {
  glfwSetErrorCallback(log_glfw_error);
  if (!glfwInit()) return Error{"cannot initialise GLFW (no display? run under xvfb-run)"};
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_FALSE);
  std::unique_ptr<GlWindow> w(new GlWindow());
  w->window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!w->window_) {
    glfwTerminate();
    return Error{"cannot create a " + std::to_string(width) + "x" + std::to_string(height) +
                 " window with an OpenGL 3.3 core context"};
  }
  glfwMakeContextCurrent(w->window_);
  glfwSwapInterval(0);  // the loop paces itself (--fps); Xvfb has no vsync anyway
  return w;
}

GlWindow::~GlWindow() {
  if (window_) glfwDestroyWindow(window_);
  glfwTerminate();
}

double GlWindow::framebuffer_scale() const {
  int ww = 0, wh = 0, fw = 0, fh = 0;
  glfwGetWindowSize(window_, &ww, &wh);
  glfwGetFramebufferSize(window_, &fw, &fh);
  return ww > 0 ? static_cast<double>(fw) / ww : 1.0;
}

std::string GlWindow::renderer() const {
  const auto* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return r ? r : "unknown";
}

Status write_screenshot(const std::string& path, int width, int height) {
  std::vector<unsigned char> pixels(static_cast<size_t>(width) * static_cast<size_t>(height) * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, pixels.data());
  const size_t row = static_cast<size_t>(width) * 3;
  std::vector<unsigned char> flipped(pixels.size());
  for (int y = 0; y < height; ++y)
    std::copy_n(pixels.data() + static_cast<size_t>(height - 1 - y) * row, row,
                flipped.data() + static_cast<size_t>(y) * row);
  if (!stbi_write_png(path.c_str(), width, height, 3, flipped.data(), static_cast<int>(row)))
    return Error{"cannot write screenshot " + path};
  return {};
}

}  // namespace slam::viewer
