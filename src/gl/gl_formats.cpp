// Format tables.
#include "gl_formats.h"

#include <epoxy/gl.h>

namespace penumbra::gl {
namespace {

int componentIndex(int components) {
  return components == 1 ? 0 : (components == 2 ? 1 : 2);
}

}  // namespace

unsigned internalFormat(const ChannelLayout& layout) {
  static const GLenum formats[4][3] = {
      {GL_R32F, GL_RG32F, GL_RGBA32F},  // Float32
      {GL_R16F, GL_RG16F, GL_RGBA16F},  // Float16
      {GL_R16, GL_RG16, GL_RGBA16},     // Unorm16
      {GL_R8, GL_RG8, GL_RGBA8},        // Unorm8
  };
  return formats[int(layout.format)][componentIndex(layout.componentsPerTexel)];
}

std::string imageFormatQualifier(const ChannelLayout& layout) {
  static const char* suffixes[4] = {"32f", "16f", "16", "8"};
  static const char* components[3] = {"r", "rg", "rgba"};
  return std::string(components[componentIndex(layout.componentsPerTexel)]) +
         suffixes[int(layout.format)];
}

}  // namespace penumbra::gl
