// GL programs built from the shader library (compile errors name the original files and lines),
// uniform setters, and the buffers and textures the passes share.
#pragma once

#include <cstddef>
#include <glm/glm.hpp>
#include <span>
#include <string_view>

#include "penumbra/shader_library.h"

namespace penumbra::gl {

class Program {
 public:
  static Program compute(const ShaderLibrary& library, std::string_view path,
                         std::span<const ShaderDefine> defines = {});
  static Program graphics(const ShaderLibrary& library, std::string_view vertexPath,
                          std::string_view fragmentPath,
                          std::span<const ShaderDefine> defines = {});
  Program(Program&& other) noexcept;
  Program& operator=(Program&& other) noexcept;
  ~Program();
  Program(const Program&) = delete;
  Program& operator=(const Program&) = delete;

  unsigned id() const { return program_; }
  void use() const;
  // Runs groups work groups and makes their image and buffer writes visible to what follows.
  void dispatch(unsigned groupsX, unsigned groupsY = 1, unsigned groupsZ = 1) const;

  // Uniform setters; a uniform the compiler removed is silently skipped (GL semantics).
  void set(const char* name, int v) const;
  void set(const char* name, unsigned v) const;
  void set(const char* name, float v) const;
  void set(const char* name, glm::vec2 v) const;
  void set(const char* name, glm::vec3 v) const;
  void set(const char* name, const glm::mat4& v) const;

 private:
  explicit Program(unsigned program) : program_(program) {}
  unsigned program_ = 0;
};

// An immutable-storage buffer for shader storage or uniform blocks.
class Buffer {
 public:
  explicit Buffer(std::span<const std::byte> data);
  explicit Buffer(size_t bytes);
  Buffer(Buffer&& other) noexcept;
  ~Buffer();
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  void bindStorage(unsigned binding) const;
  void bindUniform(unsigned binding) const;
  void read(std::span<std::byte> out) const;
  size_t size() const { return bytes_; }
  unsigned id() const { return buffer_; }

 private:
  unsigned buffer_ = 0;
  size_t bytes_ = 0;
};

// An owned GL texture name.
class Texture {
 public:
  Texture() = default;
  explicit Texture(unsigned target);
  Texture(Texture&& other) noexcept;
  Texture& operator=(Texture&& other) noexcept;
  ~Texture();
  Texture(const Texture&) = delete;
  Texture& operator=(const Texture&) = delete;

  unsigned id() const { return texture_; }

 private:
  unsigned texture_ = 0;
};

}  // namespace penumbra::gl
