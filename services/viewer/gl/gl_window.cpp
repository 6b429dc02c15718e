// GLFW window + GL 3.3 core context, and PNG screenshots of the back buffer (see gl_window.hpp).
#include "viewer/gl/gl_window.hpp"

#include <spdlog/spdlog.h>

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#endif

#include "common/core/guarded_callback.hpp"
#include "viewer/gl/display_loss.hpp"

namespace slam::viewer {
namespace {

void log_glfw_error(int code, const char* description) {
  guarded_callback("GLFW error", [&] { spdlog::error("GLFW error {}: {}", code, description); });
}

}  // namespace

Result<std::unique_ptr<GlWindow>> GlWindow::create(const std::string& title, int width, int height) {
  glfwSetErrorCallback(log_glfw_error);
  if (!glfwInit()) return Error{"cannot initialise GLFW (no display? run under xvfb-run)"};
  end_process_on_display_loss();
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
#if defined(__SANITIZE_ADDRESS__)
  // The leak check runs now, while the GL driver is still loaded: at exit glfwTerminate has unloaded
  // it, its frames show as "<unknown module>" and scripts/sanitize.supp cannot name them.
  __lsan_do_leak_check();
#endif
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

RgbImage read_back_buffer(int width, int height) {
  RgbImage image;
  image.width = width;
  image.height = height;
  image.bottom_up = true;
  image.pixels.resize(static_cast<size_t>(width) * static_cast<size_t>(height) * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, image.pixels.data());
  return image;
}

Status write_screenshot(const std::string& path, int width, int height) {
  return write_png(path, read_back_buffer(width, height));
}

}  // namespace slam::viewer
