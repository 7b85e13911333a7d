// Compute program compilation with translated logs, and storage buffers.
#include "penumbra/gl/compute_program.h"

#include <epoxy/gl.h>

#include <string>

#include "penumbra/error.h"
#include "penumbra/gl/context.h"

namespace penumbra::gl {
namespace {

std::string shaderLog(GLuint shader) {
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::string log(size_t(std::max(length, 1)), '\0');
  glGetShaderInfoLog(shader, length, nullptr, log.data());
  return log.c_str();
}

std::string programLog(GLuint program) {
  GLint length = 0;
  glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
  std::string log(size_t(std::max(length, 1)), '\0');
  glGetProgramInfoLog(program, length, nullptr, log.data());
  return log.c_str();
}

}  // namespace

ComputeProgram::ComputeProgram(const ShaderLibrary& library, std::string_view path,
                               std::span<const ShaderDefine> defines) {
  const ExpandedShader expanded = library.expand(path, defines);
  GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
  const char* text = expanded.source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint compiled = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &compiled);
  if (compiled != GL_TRUE) {
    const std::string log = expanded.translateLog(shaderLog(shader));
    glDeleteShader(shader);
    throw Error("compiling " + std::string(path) + " failed:\n" + log);
  }
  program_ = glCreateProgram();
  glAttachShader(program_, shader);
  glLinkProgram(program_);
  glDeleteShader(shader);
  GLint linked = GL_FALSE;
  glGetProgramiv(program_, GL_LINK_STATUS, &linked);
  if (linked != GL_TRUE) {
    const std::string log = expanded.translateLog(programLog(program_));
    glDeleteProgram(program_);
    throw Error("linking " + std::string(path) + " failed:\n" + log);
  }
  checkErrors("ComputeProgram");
}

ComputeProgram::~ComputeProgram() {
  glDeleteProgram(program_);
}

void ComputeProgram::dispatch(unsigned groupsX, unsigned groupsY, unsigned groupsZ) const {
  glUseProgram(program_);
  glDispatchCompute(groupsX, groupsY, groupsZ);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  checkErrors("ComputeProgram::dispatch");
}

StorageBuffer::StorageBuffer(std::span<const std::byte> data, bool readable) : bytes_(data.size()) {
  glCreateBuffers(1, &buffer_);
  glNamedBufferStorage(buffer_, GLsizeiptr(bytes_), data.data(),
                       readable ? GL_MAP_READ_BIT : GLbitfield(0));
  checkErrors("StorageBuffer");
}

StorageBuffer::StorageBuffer(size_t bytes) : bytes_(bytes) {
  glCreateBuffers(1, &buffer_);
  glNamedBufferStorage(buffer_, GLsizeiptr(bytes_), nullptr,
                       GL_DYNAMIC_STORAGE_BIT | GL_MAP_READ_BIT);
  checkErrors("StorageBuffer");
}

StorageBuffer::~StorageBuffer() {
  glDeleteBuffers(1, &buffer_);
}

void StorageBuffer::bind(unsigned binding) const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, buffer_);
}

void StorageBuffer::read(std::span<std::byte> out) const {
  glGetNamedBufferSubData(buffer_, 0, GLsizeiptr(std::min(out.size(), bytes_)), out.data());
  checkErrors("StorageBuffer::read");
}

}  // namespace penumbra::gl
