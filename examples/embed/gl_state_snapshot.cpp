// Every query goes through glGet*: the snapshot sees what the driver holds, not what the host
// believes it set.
#include "gl_state_snapshot.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <sstream>

namespace {

template <typename T>
std::string join(const T* values, int count) {
  std::ostringstream text;
  for (int i = 0; i < count; ++i) text << (i ? " " : "") << values[i];
  return text.str();
}

std::string integers(GLenum name, int count = 1) {
  GLint values[4] = {};
  glGetIntegerv(name, values);
  return join(values, count);
}

std::string floats(GLenum name, int count) {
  GLfloat values[4] = {};
  glGetFloatv(name, values);
  return join(values, count);
}

std::string indexed(GLenum name, GLuint index) {
  GLint64 value = 0;
  glGetInteger64i_v(name, index, &value);
  return std::to_string(value);
}

int limit(GLenum name, int most) {
  GLint value = 0;
  glGetIntegerv(name, &value);
  return std::min(int(value), most);
}

}  // namespace

GlStateSnapshot takeGlStateSnapshot(std::span<const unsigned> hostTextures) {
  GlStateSnapshot s;
  const struct {
    const char* name;
    GLenum value;
    int count;
  } single[] = {
      {"program", GL_CURRENT_PROGRAM, 1},
      {"program pipeline", GL_PROGRAM_PIPELINE_BINDING, 1},
      {"vertex array", GL_VERTEX_ARRAY_BINDING, 1},
      {"draw framebuffer", GL_DRAW_FRAMEBUFFER_BINDING, 1},
      {"read framebuffer", GL_READ_FRAMEBUFFER_BINDING, 1},
      {"renderbuffer", GL_RENDERBUFFER_BINDING, 1},
      {"transform feedback", GL_TRANSFORM_FEEDBACK_BINDING, 1},
      {"active texture", GL_ACTIVE_TEXTURE, 1},
      {"array buffer", GL_ARRAY_BUFFER_BINDING, 1},
      {"element array buffer", GL_ELEMENT_ARRAY_BUFFER_BINDING, 1},
      {"uniform buffer", GL_UNIFORM_BUFFER_BINDING, 1},
      {"shader storage buffer", GL_SHADER_STORAGE_BUFFER_BINDING, 1},
      {"pixel pack buffer", GL_PIXEL_PACK_BUFFER_BINDING, 1},
      {"pixel unpack buffer", GL_PIXEL_UNPACK_BUFFER_BINDING, 1},
      {"copy read buffer", GL_COPY_READ_BUFFER_BINDING, 1},
      {"copy write buffer", GL_COPY_WRITE_BUFFER_BINDING, 1},
      {"dispatch indirect buffer", GL_DISPATCH_INDIRECT_BUFFER_BINDING, 1},
      {"draw indirect buffer", GL_DRAW_INDIRECT_BUFFER_BINDING, 1},
      {"viewport", GL_VIEWPORT, 4},
      {"scissor box", GL_SCISSOR_BOX, 4},
      {"color writemask", GL_COLOR_WRITEMASK, 4},
      {"depth writemask", GL_DEPTH_WRITEMASK, 1},
      {"depth func", GL_DEPTH_FUNC, 1},
      {"cull face mode", GL_CULL_FACE_MODE, 1},
      {"front face", GL_FRONT_FACE, 1},
      {"polygon mode", GL_POLYGON_MODE, 1},
      {"blend src rgb", GL_BLEND_SRC_RGB, 1},
      {"blend dst rgb", GL_BLEND_DST_RGB, 1},
      {"blend equation rgb", GL_BLEND_EQUATION_RGB, 1},
      {"clip origin", GL_CLIP_ORIGIN, 1},
      {"clip depth mode", GL_CLIP_DEPTH_MODE, 1},
      {"pack alignment", GL_PACK_ALIGNMENT, 1},
      {"unpack alignment", GL_UNPACK_ALIGNMENT, 1},
      {"pack row length", GL_PACK_ROW_LENGTH, 1},
      {"unpack row length", GL_UNPACK_ROW_LENGTH, 1},
  };
  for (const auto& q : single) s[q.name] = integers(q.value, q.count);
  s["depth range"] = floats(GL_DEPTH_RANGE, 2);
  s["clear color"] = floats(GL_COLOR_CLEAR_VALUE, 4);
  s["clear depth"] = floats(GL_DEPTH_CLEAR_VALUE, 1);

  const struct {
    const char* name;
    GLenum value;
  } enables[] = {
      {"blend", GL_BLEND},
      {"cull face", GL_CULL_FACE},
      {"depth test", GL_DEPTH_TEST},
      {"depth clamp", GL_DEPTH_CLAMP},
      {"scissor test", GL_SCISSOR_TEST},
      {"stencil test", GL_STENCIL_TEST},
      {"multisample", GL_MULTISAMPLE},
      {"sample shading", GL_SAMPLE_SHADING},
      {"sample alpha to coverage", GL_SAMPLE_ALPHA_TO_COVERAGE},
      {"framebuffer srgb", GL_FRAMEBUFFER_SRGB},
      {"rasterizer discard", GL_RASTERIZER_DISCARD},
      {"polygon offset fill", GL_POLYGON_OFFSET_FILL},
      {"primitive restart", GL_PRIMITIVE_RESTART},
      {"dither", GL_DITHER},
      {"color logic op", GL_COLOR_LOGIC_OP},
      {"program point size", GL_PROGRAM_POINT_SIZE},
      {"seamless cube maps", GL_TEXTURE_CUBE_MAP_SEAMLESS},
      {"debug output", GL_DEBUG_OUTPUT},
      {"debug output synchronous", GL_DEBUG_OUTPUT_SYNCHRONOUS},
  };
  for (const auto& e : enables)
    s[std::string("enabled ") + e.name] = glIsEnabled(e.value) ? "1" : "0";

  // The host's debug callback and its user pointer, as pointers.
  for (const auto& [name, value] : {std::pair{"debug callback", GL_DEBUG_CALLBACK_FUNCTION},
                                    std::pair{"debug user param", GL_DEBUG_CALLBACK_USER_PARAM}}) {
    void* pointer = nullptr;
    glGetPointerv(value, &pointer);
    std::ostringstream text;
    text << pointer;
    s[name] = text.str();
  }

  GLint active = 0;
  glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
  for (int unit = 0; unit < limit(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, 16); ++unit) {
    glActiveTexture(GLenum(GL_TEXTURE0 + unit));
    const std::string at = " unit " + std::to_string(unit);
    s["texture 2d" + at] = integers(GL_TEXTURE_BINDING_2D);
    s["texture 2d array" + at] = integers(GL_TEXTURE_BINDING_2D_ARRAY);
    s["texture 2d multisample array" + at] = integers(GL_TEXTURE_BINDING_2D_MULTISAMPLE_ARRAY);
    s["sampler" + at] = integers(GL_SAMPLER_BINDING);
  }
  glActiveTexture(GLenum(active));

  for (int unit = 0; unit < limit(GL_MAX_IMAGE_UNITS, 16); ++unit) {
    const std::string at = " " + std::to_string(unit);
    s["image unit" + at] = indexed(GL_IMAGE_BINDING_NAME, unit) + " level " +
                           indexed(GL_IMAGE_BINDING_LEVEL, unit) + " layered " +
                           indexed(GL_IMAGE_BINDING_LAYERED, unit) + " layer " +
                           indexed(GL_IMAGE_BINDING_LAYER, unit) + " access " +
                           indexed(GL_IMAGE_BINDING_ACCESS, unit) + " format " +
                           indexed(GL_IMAGE_BINDING_FORMAT, unit);
  }
  const struct {
    const char* name;
    GLenum count, binding, start, size;
  } ranges[] = {
      {"uniform buffer", GL_MAX_UNIFORM_BUFFER_BINDINGS, GL_UNIFORM_BUFFER_BINDING,
       GL_UNIFORM_BUFFER_START, GL_UNIFORM_BUFFER_SIZE},
      {"shader storage buffer", GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS,
       GL_SHADER_STORAGE_BUFFER_BINDING, GL_SHADER_STORAGE_BUFFER_START,
       GL_SHADER_STORAGE_BUFFER_SIZE},
      {"atomic counter buffer", GL_MAX_ATOMIC_COUNTER_BUFFER_BINDINGS,
       GL_ATOMIC_COUNTER_BUFFER_BINDING, GL_ATOMIC_COUNTER_BUFFER_START,
       GL_ATOMIC_COUNTER_BUFFER_SIZE},
  };
  for (const auto& r : ranges) {
    for (int i = 0; i < limit(r.count, 16); ++i) {
      s[std::string(r.name) + " " + std::to_string(i)] =
          indexed(r.binding, i) + " at " + indexed(r.start, i) + " size " + indexed(r.size, i);
    }
  }

  for (unsigned texture : hostTextures) {
    const GLenum parameters[] = {GL_TEXTURE_MIN_FILTER,   GL_TEXTURE_MAG_FILTER,
                                 GL_TEXTURE_WRAP_S,       GL_TEXTURE_WRAP_T,
                                 GL_TEXTURE_COMPARE_MODE, GL_TEXTURE_COMPARE_FUNC,
                                 GL_TEXTURE_BASE_LEVEL,   GL_TEXTURE_MAX_LEVEL,
                                 GL_TEXTURE_SWIZZLE_R,    GL_DEPTH_STENCIL_TEXTURE_MODE};
    for (GLenum p : parameters) {
      GLint value = 0;
      glGetTextureParameteriv(texture, p, &value);
      s["texture " + std::to_string(texture) + " parameter " + std::to_string(p)] =
          std::to_string(value);
    }
  }
  return s;
}

std::string describeDifferences(const GlStateSnapshot& before, const GlStateSnapshot& after) {
  std::string lines;
  for (const auto& [what, value] : before) {
    const auto it = after.find(what);
    const std::string now = it == after.end() ? "(missing)" : it->second;
    if (now != value) lines += what + ": " + value + " -> " + now + "\n";
  }
  return lines;
}
