// Capturing, restoring and comparing GL state with glGet* queries. Restoring binds every recorded
// item, changed or not: comparing first would cost as many queries as binding does. Names are
// checked (glIs*) before they are bound again: penumbra may delete its own objects meanwhile.
#include "gl_state.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

namespace penumbra::gl {
namespace {

GLint integer(GLenum query) {
  GLint value = 0;
  glGetIntegerv(query, &value);
  return value;
}

GLuint name(GLenum query) {
  return GLuint(integer(query));
}

GLint integerAt(GLenum query, int index) {
  GLint value = 0;
  glGetIntegeri_v(query, GLuint(index), &value);
  return value;
}

GLint64 integer64At(GLenum query, int index) {
  GLint64 value = 0;
  glGetInteger64i_v(query, GLuint(index), &value);
  return value;
}

GLfloat real(GLenum query) {
  GLfloat value = 0.0f;
  glGetFloatv(query, &value);
  return value;
}

std::vector<GlStateSnapshot::BufferRange> captureBufferRanges(GLenum binding, GLenum start,
                                                              GLenum size, int count) {
  std::vector<GlStateSnapshot::BufferRange> ranges(size_t(std::max(count, 0)));
  for (int i = 0; i < count; ++i) {
    GlStateSnapshot::BufferRange& r = ranges[size_t(i)];
    r.buffer = GLuint(integerAt(binding, i));
    // A deleted buffer leaves its range behind on some drivers: an empty binding has none.
    if (r.buffer != 0) r = {r.buffer, integer64At(start, i), integer64At(size, i)};
  }
  return ranges;
}

// `name` if it still names an object (`exists`: glIsTexture, glIsBuffer...), else 0.
using IsObject = GLboolean(GLAPIENTRY*)(GLuint);
GLuint existing(GLuint name, IsObject exists) {
  return name != 0 && exists(name) ? name : 0;
}

// A texture name may have been reused by a texture of another target, which glBindTexture
// refuses.
GLuint existingTexture(GLuint texture, GLenum target) {
  if (existing(texture, glIsTexture) == 0) return 0;
  GLint actual = 0;
  glGetTextureParameteriv(texture, GL_TEXTURE_TARGET, &actual);
  return GLenum(actual) == target ? texture : 0;
}

void restoreBufferRanges(GLenum target, const std::vector<GlStateSnapshot::BufferRange>& ranges) {
  for (size_t i = 0; i < ranges.size(); ++i) {
    const GlStateSnapshot::BufferRange& r = ranges[i];
    const GLuint buffer = existing(r.buffer, glIsBuffer);
    GLint64 bufferSize = 0;
    if (buffer != 0 && r.size > 0) {
      glGetNamedBufferParameteri64v(buffer, GL_BUFFER_SIZE, &bufferSize);
    }
    if (buffer != 0 && r.size > 0 && r.start + r.size <= bufferSize) {
      glBindBufferRange(target, GLuint(i), buffer, GLintptr(r.start), GLsizeiptr(r.size));
    } else {
      glBindBufferBase(target, GLuint(i), r.size > 0 ? 0 : buffer);
    }
  }
}

// Text of recorded values for differences().
std::string show(GLboolean value) {
  return value ? "true" : "false";
}
std::string show(GLint value) {
  return std::to_string(value);
}
std::string show(GLuint value) {
  return std::to_string(value);
}
std::string show(GLint64 value) {
  return std::to_string(value);
}
std::string show(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}
std::string showEnum(GLenum value) {
  char hex[16];
  std::snprintf(hex, sizeof hex, "0x%04x", value);
  return hex;
}
template <class T, size_t N>
std::string show(const std::array<T, N>& values) {
  std::string text = "(";
  for (size_t i = 0; i < N; ++i) text += (i ? ", " : "") + show(values[i]);
  return text + ")";
}
std::string show(const GlStateSnapshot::ImageUnit& u) {
  return "(texture " + show(u.texture) + ", level " + show(u.level) + ", layered " +
         show(u.layered) + ", layer " + show(u.layer) + ", access " + showEnum(u.access) +
         ", format " + showEnum(u.format) + ")";
}
std::string show(const GlStateSnapshot::BufferRange& r) {
  return "(buffer " + show(r.buffer) + ", start " + show(r.start) + ", size " + show(r.size) + ")";
}

class DifferenceList {
 public:
  template <class T>
  void compare(const std::string& item, const T& before, const T& after) {
    if (!(before == after)) add(item, show(before), show(after));
  }
  void compareEnum(const std::string& item, GLenum before, GLenum after) {
    if (before != after) add(item, showEnum(before), showEnum(after));
  }
  template <class T, class Compare>
  void compareEach(const std::string& item, const std::vector<T>& before,
                   const std::vector<T>& after, Compare compareOne) {
    if (before.size() != after.size()) {
      add(item + " count", std::to_string(before.size()), std::to_string(after.size()));
    }
    for (size_t i = 0; i < std::min(before.size(), after.size()); ++i) {
      compareOne(item + " " + std::to_string(i), before[i], after[i]);
    }
  }
  std::string text() const { return text_; }

 private:
  void add(const std::string& item, const std::string& before, const std::string& after) {
    text_ += item + ": " + before + " -> " + after + "\n";
  }
  std::string text_;
};

}  // namespace

GlStateSnapshot GlStateSnapshot::capture(int units) {
  GlStateSnapshot s;
  s.program = name(GL_CURRENT_PROGRAM);
  s.programPipeline = name(GL_PROGRAM_PIPELINE_BINDING);
  s.vertexArray = name(GL_VERTEX_ARRAY_BINDING);
  s.drawFramebuffer = name(GL_DRAW_FRAMEBUFFER_BINDING);
  s.readFramebuffer = name(GL_READ_FRAMEBUFFER_BINDING);
  s.renderbuffer = name(GL_RENDERBUFFER_BINDING);
  for (int i = 0; i < kGlDrawBuffers; ++i) s.drawBuffers[size_t(i)] = name(GL_DRAW_BUFFER0 + i);
  s.readBuffer = name(GL_READ_BUFFER);

  glGetIntegerv(GL_VIEWPORT, s.viewport.data());
  glGetIntegerv(GL_SCISSOR_BOX, s.scissorBox.data());
  for (size_t i = 0; i < kGlCapabilities.size(); ++i) {
    s.enabled[i] = glIsEnabled(kGlCapabilities[i].value);
  }
  for (int i = 0; i < kGlDrawBuffers; ++i) {
    ColorOutput& o = s.colorOutputs[size_t(i)];
    o.blend = glIsEnabledi(GL_BLEND, GLuint(i));
    glGetBooleani_v(GL_COLOR_WRITEMASK, GLuint(i), o.colorMask.data());
    o.blendSourceRgb = GLenum(integerAt(GL_BLEND_SRC_RGB, i));
    o.blendDestinationRgb = GLenum(integerAt(GL_BLEND_DST_RGB, i));
    o.blendSourceAlpha = GLenum(integerAt(GL_BLEND_SRC_ALPHA, i));
    o.blendDestinationAlpha = GLenum(integerAt(GL_BLEND_DST_ALPHA, i));
    o.blendEquationRgb = GLenum(integerAt(GL_BLEND_EQUATION_RGB, i));
    o.blendEquationAlpha = GLenum(integerAt(GL_BLEND_EQUATION_ALPHA, i));
  }
  s.depthFunc = GLenum(integer(GL_DEPTH_FUNC));
  glGetBooleanv(GL_DEPTH_WRITEMASK, &s.depthMask);
  glGetDoublev(GL_DEPTH_RANGE, s.depthRange.data());
  s.clipOrigin = GLenum(integer(GL_CLIP_ORIGIN));
  s.clipDepthMode = GLenum(integer(GL_CLIP_DEPTH_MODE));
  s.cullFaceMode = GLenum(integer(GL_CULL_FACE_MODE));
  s.frontFace = GLenum(integer(GL_FRONT_FACE));
  GLint polygonModes[2] = {};  // front and back, equal in a core profile
  glGetIntegerv(GL_POLYGON_MODE, polygonModes);
  s.polygonMode = GLenum(polygonModes[0]);
  s.polygonOffsetFactor = real(GL_POLYGON_OFFSET_FACTOR);
  s.polygonOffsetUnits = real(GL_POLYGON_OFFSET_UNITS);
  s.minSampleShading = real(GL_MIN_SAMPLE_SHADING_VALUE);
  glGetFloatv(GL_COLOR_CLEAR_VALUE, s.clearColor.data());
  glGetDoublev(GL_DEPTH_CLEAR_VALUE, &s.clearDepth);
  s.clearStencil = integer(GL_STENCIL_CLEAR_VALUE);

  s.activeTexture = GLenum(integer(GL_ACTIVE_TEXTURE));
  const int textureUnits = std::min(units, integer(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS));
  s.textureUnits.resize(size_t(std::max(textureUnits, 0)));
  for (int unit = 0; unit < textureUnits; ++unit) {
    TextureUnit& u = s.textureUnits[size_t(unit)];
    glActiveTexture(GLenum(GL_TEXTURE0 + unit));
    for (size_t t = 0; t < kGlTextureTargets.size(); ++t) {
      u.textures[t] = name(kGlTextureTargets[t].query);
    }
    u.sampler = name(GL_SAMPLER_BINDING);
  }
  glActiveTexture(s.activeTexture);

  const int imageUnits = std::min(units, integer(GL_MAX_IMAGE_UNITS));
  s.imageUnits.resize(size_t(std::max(imageUnits, 0)));
  for (int unit = 0; unit < imageUnits; ++unit) {
    ImageUnit& u = s.imageUnits[size_t(unit)];
    u.texture = GLuint(integerAt(GL_IMAGE_BINDING_NAME, unit));
    if (u.texture == 0) continue;  // the rest is ignored: keep the defaults
    u.level = integerAt(GL_IMAGE_BINDING_LEVEL, unit);
    u.layered = integerAt(GL_IMAGE_BINDING_LAYERED, unit) ? GL_TRUE : GL_FALSE;
    u.layer = integerAt(GL_IMAGE_BINDING_LAYER, unit);
    u.access = GLenum(integerAt(GL_IMAGE_BINDING_ACCESS, unit));
    u.format = GLenum(integerAt(GL_IMAGE_BINDING_FORMAT, unit));
  }

  s.uniformBuffers = captureBufferRanges(GL_UNIFORM_BUFFER_BINDING, GL_UNIFORM_BUFFER_START,
                                         GL_UNIFORM_BUFFER_SIZE,
                                         std::min(units, integer(GL_MAX_UNIFORM_BUFFER_BINDINGS)));
  s.shaderStorageBuffers =
      captureBufferRanges(GL_SHADER_STORAGE_BUFFER_BINDING, GL_SHADER_STORAGE_BUFFER_START,
                          GL_SHADER_STORAGE_BUFFER_SIZE,
                          std::min(units, integer(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS)));
  for (size_t i = 0; i < kGlBufferTargets.size(); ++i) {
    s.buffers[i] = name(kGlBufferTargets[i].query);
  }
  for (size_t i = 0; i < kGlPixelStoreParameters.size(); ++i) {
    s.pixelStore[i] = integer(kGlPixelStoreParameters[i].value);
  }
  return s;
}

void GlStateSnapshot::restore() const {
  glUseProgram(existing(program, glIsProgram));
  glBindProgramPipeline(existing(programPipeline, glIsProgramPipeline));
  glBindVertexArray(existing(vertexArray, glIsVertexArray));
  const GLuint draw = existing(drawFramebuffer, glIsFramebuffer);
  const GLuint read = existing(readFramebuffer, glIsFramebuffer);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, draw);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, read);
  glBindRenderbuffer(GL_RENDERBUFFER, existing(renderbuffer, glIsRenderbuffer));
  // A framebuffer's own state: set only where it changed, since glNamedFramebufferDrawBuffers
  // rejects some values the default framebuffer reports (GL_BACK).
  std::array<GLenum, kGlDrawBuffers> currentDrawBuffers{};
  for (int i = 0; i < kGlDrawBuffers; ++i) {
    currentDrawBuffers[size_t(i)] = name(GL_DRAW_BUFFER0 + i);
  }
  if (draw == drawFramebuffer && currentDrawBuffers != drawBuffers) {
    if (draw == 0) {
      glNamedFramebufferDrawBuffer(0, drawBuffers[0]);
    } else {
      glNamedFramebufferDrawBuffers(draw, kGlDrawBuffers, drawBuffers.data());
    }
  }
  if (read == readFramebuffer && name(GL_READ_BUFFER) != readBuffer) {
    glNamedFramebufferReadBuffer(read, readBuffer);
  }

  glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
  glScissor(scissorBox[0], scissorBox[1], scissorBox[2], scissorBox[3]);
  for (size_t i = 0; i < kGlCapabilities.size(); ++i) {
    (enabled[i] ? glEnable : glDisable)(kGlCapabilities[i].value);
  }
  for (int i = 0; i < kGlDrawBuffers; ++i) {
    const ColorOutput& o = colorOutputs[size_t(i)];
    (o.blend ? glEnablei : glDisablei)(GL_BLEND, GLuint(i));
    glColorMaski(GLuint(i), o.colorMask[0], o.colorMask[1], o.colorMask[2], o.colorMask[3]);
    glBlendFuncSeparatei(GLuint(i), o.blendSourceRgb, o.blendDestinationRgb, o.blendSourceAlpha,
                         o.blendDestinationAlpha);
    glBlendEquationSeparatei(GLuint(i), o.blendEquationRgb, o.blendEquationAlpha);
  }
  glDepthFunc(depthFunc);
  glDepthMask(depthMask);
  glDepthRange(depthRange[0], depthRange[1]);
  glClipControl(clipOrigin, clipDepthMode);
  glCullFace(cullFaceMode);
  glFrontFace(frontFace);
  glPolygonMode(GL_FRONT_AND_BACK, polygonMode);
  glPolygonOffset(polygonOffsetFactor, polygonOffsetUnits);
  glMinSampleShading(minSampleShading);
  glClearColor(clearColor[0], clearColor[1], clearColor[2], clearColor[3]);
  glClearDepth(clearDepth);
  glClearStencil(clearStencil);

  // glBindTexture with each target, since glBindTextureUnit cannot unbind a single target.
  for (size_t unit = 0; unit < textureUnits.size(); ++unit) {
    glActiveTexture(GLenum(GL_TEXTURE0 + unit));
    for (size_t t = 0; t < kGlTextureTargets.size(); ++t) {
      const GLenum target = kGlTextureTargets[t].target;
      glBindTexture(target, existingTexture(textureUnits[unit].textures[t], target));
    }
    glBindSampler(GLuint(unit), existing(textureUnits[unit].sampler, glIsSampler));
  }
  glActiveTexture(activeTexture);
  for (size_t unit = 0; unit < imageUnits.size(); ++unit) {
    const ImageUnit& u = imageUnits[unit];
    if (existing(u.texture, glIsTexture) != 0) {
      glBindImageTexture(GLuint(unit), u.texture, u.level, u.layered, u.layer, u.access, u.format);
    } else {
      const ImageUnit empty;
      glBindImageTexture(GLuint(unit), 0, empty.level, empty.layered, empty.layer, empty.access,
                         empty.format);
    }
  }
  // glBindBufferBase and glBindBufferRange also bind the generic binding point: the indexed
  // bindings go first, the generic ones after.
  restoreBufferRanges(GL_UNIFORM_BUFFER, uniformBuffers);
  restoreBufferRanges(GL_SHADER_STORAGE_BUFFER, shaderStorageBuffers);
  for (size_t i = 0; i < kGlBufferTargets.size(); ++i) {
    glBindBuffer(kGlBufferTargets[i].target, existing(buffers[i], glIsBuffer));
  }
  for (size_t i = 0; i < kGlPixelStoreParameters.size(); ++i) {
    glPixelStorei(kGlPixelStoreParameters[i].value, pixelStore[i]);
  }
}

std::string GlStateSnapshot::differences(const GlStateSnapshot& a) const {
  DifferenceList d;
  d.compare("program", program, a.program);
  d.compare("program pipeline", programPipeline, a.programPipeline);
  d.compare("vertex array", vertexArray, a.vertexArray);
  d.compare("draw framebuffer", drawFramebuffer, a.drawFramebuffer);
  d.compare("read framebuffer", readFramebuffer, a.readFramebuffer);
  d.compare("renderbuffer", renderbuffer, a.renderbuffer);
  for (size_t i = 0; i < drawBuffers.size(); ++i) {
    d.compareEnum("draw buffer " + std::to_string(i), drawBuffers[i], a.drawBuffers[i]);
  }
  d.compareEnum("read buffer", readBuffer, a.readBuffer);

  d.compare("viewport", viewport, a.viewport);
  d.compare("scissor box", scissorBox, a.scissorBox);
  for (size_t i = 0; i < kGlCapabilities.size(); ++i) {
    d.compare(kGlCapabilities[i].name, enabled[i], a.enabled[i]);
  }
  for (size_t i = 0; i < colorOutputs.size(); ++i) {
    const ColorOutput& o = colorOutputs[i];
    const ColorOutput& ao = a.colorOutputs[i];
    const std::string output = "draw buffer " + std::to_string(i) + " ";
    d.compare(output + "GL_BLEND", o.blend, ao.blend);
    d.compare(output + "colour mask", o.colorMask, ao.colorMask);
    d.compareEnum(output + "blend source RGB", o.blendSourceRgb, ao.blendSourceRgb);
    d.compareEnum(output + "blend destination RGB", o.blendDestinationRgb, ao.blendDestinationRgb);
    d.compareEnum(output + "blend source alpha", o.blendSourceAlpha, ao.blendSourceAlpha);
    d.compareEnum(output + "blend destination alpha", o.blendDestinationAlpha,
                  ao.blendDestinationAlpha);
    d.compareEnum(output + "blend equation RGB", o.blendEquationRgb, ao.blendEquationRgb);
    d.compareEnum(output + "blend equation alpha", o.blendEquationAlpha, ao.blendEquationAlpha);
  }
  d.compareEnum("depth func", depthFunc, a.depthFunc);
  d.compare("depth mask", depthMask, a.depthMask);
  d.compare("depth range", depthRange, a.depthRange);
  d.compareEnum("clip origin", clipOrigin, a.clipOrigin);
  d.compareEnum("clip depth mode", clipDepthMode, a.clipDepthMode);
  d.compareEnum("cull face mode", cullFaceMode, a.cullFaceMode);
  d.compareEnum("front face", frontFace, a.frontFace);
  d.compareEnum("polygon mode", polygonMode, a.polygonMode);
  d.compare("polygon offset factor", double(polygonOffsetFactor), double(a.polygonOffsetFactor));
  d.compare("polygon offset units", double(polygonOffsetUnits), double(a.polygonOffsetUnits));
  d.compare("min sample shading", double(minSampleShading), double(a.minSampleShading));
  d.compare("clear colour", clearColor, a.clearColor);
  d.compare("clear depth", clearDepth, a.clearDepth);
  d.compare("clear stencil", clearStencil, a.clearStencil);

  d.compareEnum("active texture", activeTexture, a.activeTexture);
  d.compareEach("texture unit", textureUnits, a.textureUnits,
                [&d](const std::string& unit, const TextureUnit& u, const TextureUnit& au) {
                  for (size_t t = 0; t < kGlTextureTargets.size(); ++t) {
                    d.compare(unit + " " + kGlTextureTargets[t].name, u.textures[t],
                              au.textures[t]);
                  }
                  d.compare(unit + " sampler", u.sampler, au.sampler);
                });
  const auto compareOne = [&d](const std::string& item, const auto& before, const auto& after) {
    d.compare(item, before, after);
  };
  d.compareEach("image unit", imageUnits, a.imageUnits, compareOne);
  d.compareEach("GL_UNIFORM_BUFFER binding", uniformBuffers, a.uniformBuffers, compareOne);
  d.compareEach("GL_SHADER_STORAGE_BUFFER binding", shaderStorageBuffers, a.shaderStorageBuffers,
                compareOne);
  for (size_t i = 0; i < kGlBufferTargets.size(); ++i) {
    d.compare(std::string("generic ") + kGlBufferTargets[i].name + " binding", buffers[i],
              a.buffers[i]);
  }
  for (size_t i = 0; i < kGlPixelStoreParameters.size(); ++i) {
    d.compare(kGlPixelStoreParameters[i].name, pixelStore[i], a.pixelStore[i]);
  }
  return d.text();
}

}  // namespace penumbra::gl
