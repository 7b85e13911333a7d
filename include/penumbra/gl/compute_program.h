// A compute program built from the shader library, and the storage buffers it reads and writes.
#pragma once

#include <cstddef>
#include <span>
#include <string_view>

#include "penumbra/shader_library.h"

namespace penumbra::gl {

class ComputeProgram {
 public:
  // Expands `path` from the library and compiles it; compile and link errors throw Error with
  // the compiler log translated to the original file names and lines.
  ComputeProgram(const ShaderLibrary& library, std::string_view path,
                 std::span<const ShaderDefine> defines = {});
  ~ComputeProgram();
  ComputeProgram(const ComputeProgram&) = delete;
  ComputeProgram& operator=(const ComputeProgram&) = delete;

  unsigned id() const { return program_; }
  // Runs groups.x*y*z work groups and waits for their writes to be visible to buffer reads.
  void dispatch(unsigned groupsX, unsigned groupsY = 1, unsigned groupsZ = 1) const;

 private:
  unsigned program_ = 0;
};

// An immutable-storage shader storage buffer.
class StorageBuffer {
 public:
  StorageBuffer(std::span<const std::byte> data, bool readable);
  explicit StorageBuffer(size_t bytes);
  ~StorageBuffer();
  StorageBuffer(const StorageBuffer&) = delete;
  StorageBuffer& operator=(const StorageBuffer&) = delete;

  void bind(unsigned binding) const;
  void read(std::span<std::byte> out) const;
  size_t size() const { return bytes_; }

 private:
  unsigned buffer_ = 0;
  size_t bytes_ = 0;
};

}  // namespace penumbra::gl
