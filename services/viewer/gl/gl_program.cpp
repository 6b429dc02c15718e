// GLSL program building with errors as values (see gl_program.hpp).
#include "viewer/gl/gl_program.hpp"

#include <vector>

namespace slam::viewer {
namespace {

Result<GLuint> compile(const char* name, GLenum kind, const char* src) {
  const GLuint s = glCreateShader(kind);
  glShaderSource(s, 1, &src, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (ok) return s;
  GLint len = 0;
  glGetShaderiv(s, GL_INFO_LOG_LENGTH, &len);
  std::vector<char> log(static_cast<size_t>(len) + 1, '\0');
  glGetShaderInfoLog(s, len, nullptr, log.data());
  glDeleteShader(s);
  return Error{std::string(name) + (kind == GL_VERTEX_SHADER ? " vertex" : " fragment") +
               " shader does not compile: " + log.data()};
}

}  // namespace

Result<GlProgram> GlProgram::build(const char* name, const char* vertex_src, const char* fragment_src) {
  auto vs = compile(name, GL_VERTEX_SHADER, vertex_src);
  if (!vs) return vs.error();
  auto fs = compile(name, GL_FRAGMENT_SHADER, fragment_src);
  if (!fs) {
    glDeleteShader(*vs);
    return fs.error();
  }
  const GLuint p = glCreateProgram();
  glAttachShader(p, *vs);
  glAttachShader(p, *fs);
  glLinkProgram(p);
  glDeleteShader(*vs);
  glDeleteShader(*fs);
  GLint ok = 0;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (ok) return GlProgram(p);
  GLint len = 0;
  glGetProgramiv(p, GL_INFO_LOG_LENGTH, &len);
  std::vector<char> log(static_cast<size_t>(len) + 1, '\0');
  glGetProgramInfoLog(p, len, nullptr, log.data());
  glDeleteProgram(p);
  return Error{std::string(name) + " program does not link: " + log.data()};
}

GlProgram::~GlProgram() {
  if (id_) glDeleteProgram(id_);
}

GlProgram& GlProgram::operator=(GlProgram&& o) noexcept {
  if (this != &o) {
    if (id_) glDeleteProgram(id_);
    id_ = std::exchange(o.id_, 0);
  }
  return *this;
}

}  // namespace slam::viewer
