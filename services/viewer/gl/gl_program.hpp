#pragma once
// A linked GLSL program, built from two sources with the compiler's log in the error, and
// deleted with its owner.
#include <string>
#include <utility>

#include "common/core/result.hpp"
#include "viewer/gl/gl_api.hpp"

namespace slam::viewer {

class GlProgram {
 public:
  GlProgram() = default;
  static Result<GlProgram> build(const char* name, const char* vertex_src, const char* fragment_src);
  ~GlProgram();
  GlProgram(GlProgram&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
  GlProgram& operator=(GlProgram&& o) noexcept;
  GlProgram(const GlProgram&) = delete;
  GlProgram& operator=(const GlProgram&) = delete;

  GLuint id() const { return id_; }
  GLint uniform(const char* name) const { return glGetUniformLocation(id_, name); }

 private:
  explicit GlProgram(GLuint id) : id_(id) {}
  GLuint id_ = 0;
};

}  // namespace slam::viewer
