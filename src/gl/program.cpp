// Program compilation with translated logs, buffers and textures.
#include "penumbra/gl/program.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <glm/gtc/type_ptr.hpp>
#include <string>
#include <utility>

#include "penumbra/error.h"
#include "penumbra/gl/context.h"

namespace penumbra::gl {
namespace {

std::string infoLog(GLuint object, bool isProgram) {
  GLint length = 0;
  if (isProgram) {
    glGetProgramiv(object, GL_INFO_LOG_LENGTH, &length);
  } else {
    glGetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
  }
  std::string log(size_t(std::max(length, 1)), '\0');
  if (isProgram) {
    glGetProgramInfoLog(object, length, nullptr, log.data());
  } else {
    glGetShaderInfoLog(object, length, nullptr, log.data());
  }
  return log.c_str();
}

GLuint compileStage(GLenum stage, const ShaderLibrary& library, std::string_view path,
                    std::span<const ShaderDefine> defines) {
  const ExpandedShader expanded = library.expand(path, defines);
  GLuint shader = glCreateShader(stage);
  const char* text = expanded.source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint compiled = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &compiled);
  if (compiled != GL_TRUE) {
    const std::string log = expanded.translateLog(infoLog(shader, false));
    glDeleteShader(shader);
    discardPendingErrors();  // the driver's debug log repeats the compile log
    throw Error("compiling " + std::string(path) + " failed:\n" + log);
  }
  return shader;
}

GLuint link(std::initializer_list<GLuint> shaders, std::string_view name) {
  GLuint program = glCreateProgram();
  for (GLuint s : shaders) glAttachShader(program, s);
  glLinkProgram(program);
  for (GLuint s : shaders) glDeleteShader(s);
  GLint linked = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &linked);
  if (linked != GL_TRUE) {
    const std::string log = infoLog(program, true);
    glDeleteProgram(program);
    discardPendingErrors();  // the driver's debug log repeats the link log
    throw Error("linking " + std::string(name) + " failed:\n" + log);
  }
  checkErrors("linking a program");
  return program;
}

}  // namespace

Program Program::compute(const ShaderLibrary& library, std::string_view path,
                         std::span<const ShaderDefine> defines) {
  return Program(link({compileStage(GL_COMPUTE_SHADER, library, path, defines)}, path));
}

Program Program::graphics(const ShaderLibrary& library, std::string_view vertexPath,
                          std::string_view fragmentPath, std::span<const ShaderDefine> defines) {
  GLuint vertex = compileStage(GL_VERTEX_SHADER, library, vertexPath, defines);
  GLuint fragment = 0;
  try {
    fragment = compileStage(GL_FRAGMENT_SHADER, library, fragmentPath, defines);
  } catch (...) {
    glDeleteShader(vertex);
    throw;
  }
  return Program(link({vertex, fragment}, fragmentPath));
}

Program::Program(Program&& other) noexcept : program_(std::exchange(other.program_, 0)) {}

Program& Program::operator=(Program&& other) noexcept {
  std::swap(program_, other.program_);
  return *this;
}

Program::~Program() {
  if (program_ != 0) glDeleteProgram(program_);
}

void Program::use() const {
  glUseProgram(program_);
}

void Program::dispatch(unsigned groupsX, unsigned groupsY, unsigned groupsZ) const {
  glUseProgram(program_);
  glDispatchCompute(groupsX, groupsY, groupsZ);
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
                  GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT |
                  GL_TEXTURE_UPDATE_BARRIER_BIT);
  checkErrors("compute dispatch");
}

void Program::set(const char* name, int v) const {
  glProgramUniform1i(program_, glGetUniformLocation(program_, name), v);
}
void Program::set(const char* name, unsigned v) const {
  glProgramUniform1ui(program_, glGetUniformLocation(program_, name), v);
}
void Program::set(const char* name, float v) const {
  glProgramUniform1f(program_, glGetUniformLocation(program_, name), v);
}
void Program::set(const char* name, glm::vec2 v) const {
  glProgramUniform2fv(program_, glGetUniformLocation(program_, name), 1, glm::value_ptr(v));
}
void Program::set(const char* name, glm::vec3 v) const {
  glProgramUniform3fv(program_, glGetUniformLocation(program_, name), 1, glm::value_ptr(v));
}
void Program::set(const char* name, const glm::mat4& v) const {
  glProgramUniformMatrix4fv(program_, glGetUniformLocation(program_, name), 1, GL_FALSE,
                            glm::value_ptr(v));
}

Buffer::Buffer(std::span<const std::byte> data) : bytes_(data.size()) {
  glCreateBuffers(1, &buffer_);
  glNamedBufferStorage(buffer_, GLsizeiptr(std::max<size_t>(bytes_, 4)), data.data(), 0);
  checkErrors("creating a buffer");
}

Buffer::Buffer(size_t bytes) : bytes_(bytes) {
  glCreateBuffers(1, &buffer_);
  glNamedBufferStorage(buffer_, GLsizeiptr(std::max<size_t>(bytes_, 4)), nullptr,
                       GL_DYNAMIC_STORAGE_BIT);
  checkErrors("creating a buffer");
}

Buffer::Buffer(Buffer&& other) noexcept
    : buffer_(std::exchange(other.buffer_, 0)), bytes_(other.bytes_) {}

Buffer::~Buffer() {
  if (buffer_ != 0) glDeleteBuffers(1, &buffer_);
}

void Buffer::bindStorage(unsigned binding) const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, buffer_);
}

void Buffer::bindUniform(unsigned binding) const {
  glBindBufferBase(GL_UNIFORM_BUFFER, binding, buffer_);
}

void Buffer::read(std::span<std::byte> out) const {
  glGetNamedBufferSubData(buffer_, 0, GLsizeiptr(std::min(out.size(), bytes_)), out.data());
  checkErrors("reading a buffer");
}

Texture::Texture(unsigned target) {
  glCreateTextures(target, 1, &texture_);
}

Texture::Texture(Texture&& other) noexcept : texture_(std::exchange(other.texture_, 0)) {}

Texture& Texture::operator=(Texture&& other) noexcept {
  std::swap(texture_, other.texture_);
  return *this;
}

Texture::~Texture() {
  if (texture_ != 0) glDeleteTextures(1, &texture_);
}

}  // namespace penumbra::gl
