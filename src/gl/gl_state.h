// The OpenGL context state penumbra's passes may change, as a comparable record, and a guard that
// puts it back: penumbra runs on a host's context as a guest, and leaves the host's state as it
// found it. Tests compare two snapshots; GlStateGuard restores one.
//
// Not covered (penumbra's passes touch none of it): viewports and scissor boxes past index 0,
// stencil functions and masks, atomic-counter and transform-feedback indexed bindings, transform
// feedback objects, queries, the element array buffer (state of the vertex array object).
#pragma once

#include <epoxy/gl.h>

#include <array>
#include <string>
#include <vector>

namespace penumbra::gl {

// A capability, a binding point or a parameter, with its name for messages.
struct GlNamedEnum {
  GLenum value;
  const char* name;
};
// A binding target and the glGetIntegerv query that names what is bound to it.
struct GlBindingPoint {
  GLenum target;
  GLenum query;
  const char* name;
};

#define PENUMBRA_GL_NAMED(e) \
  GlNamedEnum {              \
    e, #e                    \
  }
#define PENUMBRA_GL_BINDING(target, query) \
  GlBindingPoint {                         \
    target, query, #target                 \
  }

// glEnable capabilities. GL_BLEND is per draw buffer (GlStateSnapshot::ColorOutput), and the
// scissor test and clip distances are one switch for every viewport, as glEnable sets them.
inline constexpr std::array kGlCapabilities = {
    PENUMBRA_GL_NAMED(GL_DEPTH_TEST),
    PENUMBRA_GL_NAMED(GL_CULL_FACE),
    PENUMBRA_GL_NAMED(GL_SCISSOR_TEST),
    PENUMBRA_GL_NAMED(GL_STENCIL_TEST),
    PENUMBRA_GL_NAMED(GL_POLYGON_OFFSET_FILL),
    PENUMBRA_GL_NAMED(GL_POLYGON_OFFSET_LINE),
    PENUMBRA_GL_NAMED(GL_POLYGON_OFFSET_POINT),
    PENUMBRA_GL_NAMED(GL_MULTISAMPLE),
    PENUMBRA_GL_NAMED(GL_SAMPLE_SHADING),
    PENUMBRA_GL_NAMED(GL_SAMPLE_ALPHA_TO_COVERAGE),
    PENUMBRA_GL_NAMED(GL_SAMPLE_ALPHA_TO_ONE),
    PENUMBRA_GL_NAMED(GL_SAMPLE_COVERAGE),
    PENUMBRA_GL_NAMED(GL_SAMPLE_MASK),
    PENUMBRA_GL_NAMED(GL_FRAMEBUFFER_SRGB),
    PENUMBRA_GL_NAMED(GL_RASTERIZER_DISCARD),
    PENUMBRA_GL_NAMED(GL_DEPTH_CLAMP),
    PENUMBRA_GL_NAMED(GL_PROGRAM_POINT_SIZE),
    PENUMBRA_GL_NAMED(GL_PRIMITIVE_RESTART),
    PENUMBRA_GL_NAMED(GL_PRIMITIVE_RESTART_FIXED_INDEX),
    PENUMBRA_GL_NAMED(GL_TEXTURE_CUBE_MAP_SEAMLESS),
    PENUMBRA_GL_NAMED(GL_DITHER),
    PENUMBRA_GL_NAMED(GL_COLOR_LOGIC_OP),
    PENUMBRA_GL_NAMED(GL_LINE_SMOOTH),
    PENUMBRA_GL_NAMED(GL_POLYGON_SMOOTH),
    PENUMBRA_GL_NAMED(GL_CLIP_DISTANCE0),
    PENUMBRA_GL_NAMED(GL_CLIP_DISTANCE1),
    PENUMBRA_GL_NAMED(GL_CLIP_DISTANCE2),
    PENUMBRA_GL_NAMED(GL_CLIP_DISTANCE3),
    PENUMBRA_GL_NAMED(GL_CLIP_DISTANCE4),
    PENUMBRA_GL_NAMED(GL_CLIP_DISTANCE5),
    PENUMBRA_GL_NAMED(GL_CLIP_DISTANCE6),
    PENUMBRA_GL_NAMED(GL_CLIP_DISTANCE7),
    PENUMBRA_GL_NAMED(GL_DEBUG_OUTPUT),
    PENUMBRA_GL_NAMED(GL_DEBUG_OUTPUT_SYNCHRONOUS),
};

// Texture targets of each texture unit.
inline constexpr std::array kGlTextureTargets = {
    PENUMBRA_GL_BINDING(GL_TEXTURE_1D, GL_TEXTURE_BINDING_1D),
    PENUMBRA_GL_BINDING(GL_TEXTURE_1D_ARRAY, GL_TEXTURE_BINDING_1D_ARRAY),
    PENUMBRA_GL_BINDING(GL_TEXTURE_2D, GL_TEXTURE_BINDING_2D),
    PENUMBRA_GL_BINDING(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_BINDING_2D_ARRAY),
    PENUMBRA_GL_BINDING(GL_TEXTURE_2D_MULTISAMPLE, GL_TEXTURE_BINDING_2D_MULTISAMPLE),
    PENUMBRA_GL_BINDING(GL_TEXTURE_2D_MULTISAMPLE_ARRAY, GL_TEXTURE_BINDING_2D_MULTISAMPLE_ARRAY),
    PENUMBRA_GL_BINDING(GL_TEXTURE_3D, GL_TEXTURE_BINDING_3D),
    PENUMBRA_GL_BINDING(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_BINDING_CUBE_MAP),
    PENUMBRA_GL_BINDING(GL_TEXTURE_CUBE_MAP_ARRAY, GL_TEXTURE_BINDING_CUBE_MAP_ARRAY),
    PENUMBRA_GL_BINDING(GL_TEXTURE_RECTANGLE, GL_TEXTURE_BINDING_RECTANGLE),
    PENUMBRA_GL_BINDING(GL_TEXTURE_BUFFER, GL_TEXTURE_BINDING_BUFFER),
};

// Generic (non-indexed) buffer binding points.
inline constexpr std::array kGlBufferTargets = {
    PENUMBRA_GL_BINDING(GL_ARRAY_BUFFER, GL_ARRAY_BUFFER_BINDING),
    PENUMBRA_GL_BINDING(GL_UNIFORM_BUFFER, GL_UNIFORM_BUFFER_BINDING),
    PENUMBRA_GL_BINDING(GL_SHADER_STORAGE_BUFFER, GL_SHADER_STORAGE_BUFFER_BINDING),
    PENUMBRA_GL_BINDING(GL_ATOMIC_COUNTER_BUFFER, GL_ATOMIC_COUNTER_BUFFER_BINDING),
    PENUMBRA_GL_BINDING(GL_TRANSFORM_FEEDBACK_BUFFER, GL_TRANSFORM_FEEDBACK_BUFFER_BINDING),
    PENUMBRA_GL_BINDING(GL_PIXEL_PACK_BUFFER, GL_PIXEL_PACK_BUFFER_BINDING),
    PENUMBRA_GL_BINDING(GL_PIXEL_UNPACK_BUFFER, GL_PIXEL_UNPACK_BUFFER_BINDING),
    PENUMBRA_GL_BINDING(GL_DISPATCH_INDIRECT_BUFFER, GL_DISPATCH_INDIRECT_BUFFER_BINDING),
    PENUMBRA_GL_BINDING(GL_DRAW_INDIRECT_BUFFER, GL_DRAW_INDIRECT_BUFFER_BINDING),
    PENUMBRA_GL_BINDING(GL_COPY_READ_BUFFER, GL_COPY_READ_BUFFER_BINDING),
    PENUMBRA_GL_BINDING(GL_COPY_WRITE_BUFFER, GL_COPY_WRITE_BUFFER_BINDING),
    PENUMBRA_GL_BINDING(GL_QUERY_BUFFER, GL_QUERY_BUFFER_BINDING),
    PENUMBRA_GL_BINDING(GL_TEXTURE_BUFFER, GL_TEXTURE_BUFFER_BINDING),
};

// glPixelStorei parameters (the integer ones; byte swapping and LSB-first are legacy).
inline constexpr std::array kGlPixelStoreParameters = {
    PENUMBRA_GL_NAMED(GL_PACK_ALIGNMENT),      PENUMBRA_GL_NAMED(GL_PACK_ROW_LENGTH),
    PENUMBRA_GL_NAMED(GL_PACK_IMAGE_HEIGHT),   PENUMBRA_GL_NAMED(GL_PACK_SKIP_PIXELS),
    PENUMBRA_GL_NAMED(GL_PACK_SKIP_ROWS),      PENUMBRA_GL_NAMED(GL_PACK_SKIP_IMAGES),
    PENUMBRA_GL_NAMED(GL_UNPACK_ALIGNMENT),    PENUMBRA_GL_NAMED(GL_UNPACK_ROW_LENGTH),
    PENUMBRA_GL_NAMED(GL_UNPACK_IMAGE_HEIGHT), PENUMBRA_GL_NAMED(GL_UNPACK_SKIP_PIXELS),
    PENUMBRA_GL_NAMED(GL_UNPACK_SKIP_ROWS),    PENUMBRA_GL_NAMED(GL_UNPACK_SKIP_IMAGES),
};

#undef PENUMBRA_GL_NAMED
#undef PENUMBRA_GL_BINDING

// Draw buffers whose blend state, colour mask and framebuffer draw buffer are recorded; GL 4.5
// guarantees at least 8 (GL_MAX_DRAW_BUFFERS).
inline constexpr int kGlDrawBuffers = 8;

// Texture and image units, and indexed uniform and storage buffer bindings, that penumbra's passes
// use (0..7): what GlStateGuard restores unless told otherwise.
inline constexpr int kGlGuardedUnits = 8;

struct GlStateSnapshot {
  struct TextureUnit {
    std::array<GLuint, kGlTextureTargets.size()> textures{};  // in kGlTextureTargets' order
    GLuint sampler = 0;
    bool operator==(const TextureUnit&) const = default;
  };
  // glBindImageTexture's arguments. An empty unit reads as GL's defaults whatever it was unbound
  // with: the other arguments are ignored with texture 0.
  struct ImageUnit {
    GLuint texture = 0;
    GLint level = 0;
    GLboolean layered = GL_FALSE;
    GLint layer = 0;
    GLenum access = GL_READ_ONLY;
    GLenum format = GL_R8;
    bool operator==(const ImageUnit&) const = default;
  };
  // An indexed buffer binding; size 0 is the whole buffer (bound by glBindBufferBase). An empty
  // binding reads as start 0, size 0.
  struct BufferRange {
    GLuint buffer = 0;
    GLint64 start = 0;
    GLint64 size = 0;
    bool operator==(const BufferRange&) const = default;
  };
  // Per-draw-buffer fragment output state (glEnablei, glColorMaski, glBlend*Separatei).
  struct ColorOutput {
    GLboolean blend = GL_FALSE;
    std::array<GLboolean, 4> colorMask{};
    GLenum blendSourceRgb = 0, blendDestinationRgb = 0;
    GLenum blendSourceAlpha = 0, blendDestinationAlpha = 0;
    GLenum blendEquationRgb = 0, blendEquationAlpha = 0;
    bool operator==(const ColorOutput&) const = default;
  };

  // Objects bound to the context.
  GLuint program = 0;
  GLuint programPipeline = 0;
  GLuint vertexArray = 0;
  GLuint drawFramebuffer = 0;
  GLuint readFramebuffer = 0;
  GLuint renderbuffer = 0;
  // State of the bound framebuffers (not the context's), recorded since penumbra must not alter
  // a host framebuffer's; restored only where it differs.
  std::array<GLenum, kGlDrawBuffers> drawBuffers{};
  GLenum readBuffer = 0;

  // Rasterisation and per-fragment state.
  std::array<GLint, 4> viewport{};  // viewport 0: x, y, width, height
  std::array<GLint, 4> scissorBox{};
  std::array<GLboolean, kGlCapabilities.size()> enabled{};  // in kGlCapabilities' order
  std::array<ColorOutput, kGlDrawBuffers> colorOutputs{};
  GLenum depthFunc = 0;
  GLboolean depthMask = GL_FALSE;
  std::array<GLdouble, 2> depthRange{};
  GLenum clipOrigin = 0, clipDepthMode = 0;
  GLenum cullFaceMode = 0;
  GLenum frontFace = 0;
  GLenum polygonMode = 0;  // core profile: one mode for front and back
  GLfloat polygonOffsetFactor = 0.0f, polygonOffsetUnits = 0.0f;
  GLfloat minSampleShading = 0.0f;
  std::array<GLfloat, 4> clearColor{};
  GLdouble clearDepth = 0.0;
  GLint clearStencil = 0;

  // Units and buffer bindings; the units' vectors hold min(units, the implementation's count).
  GLenum activeTexture = GL_TEXTURE0;
  std::vector<TextureUnit> textureUnits;
  std::vector<ImageUnit> imageUnits;
  std::vector<BufferRange> uniformBuffers;        // indexed GL_UNIFORM_BUFFER bindings
  std::vector<BufferRange> shaderStorageBuffers;  // indexed GL_SHADER_STORAGE_BUFFER bindings
  std::array<GLuint, kGlBufferTargets.size()> buffers{};  // generic, in kGlBufferTargets' order
  std::array<GLint, kGlPixelStoreParameters.size()> pixelStore{};

  // Records the current context's state: texture and image units, and indexed uniform and storage
  // buffer bindings, below `units`. Leaves the state as it was (it visits each texture unit).
  static GlStateSnapshot capture(int units = kGlGuardedUnits);
  // Makes the current context's state this snapshot's. A binding to an object deleted since (or
  // whose name now belongs to an object of another target, or a buffer too small for the range)
  // is restored as empty, as glDelete* leaves the bindings of the current context.
  void restore() const;

  bool operator==(const GlStateSnapshot&) const = default;
  // One line per item that differs, "viewport: (0, 0, 64, 64) -> (3, 4, 50, 60)"; empty if equal.
  std::string differences(const GlStateSnapshot& after) const;
};

// Restores, when it goes out of scope, the state the context had when it was made (with texture
// and image units, and indexed buffer bindings, below `units`), but for objects deleted meanwhile
// (GlStateSnapshot::restore). Raises no GL error.
class GlStateGuard {
 public:
  explicit GlStateGuard(int units = kGlGuardedUnits) : saved_(GlStateSnapshot::capture(units)) {}
  ~GlStateGuard() { saved_.restore(); }
  GlStateGuard(const GlStateGuard&) = delete;
  GlStateGuard& operator=(const GlStateGuard&) = delete;

  const GlStateSnapshot& saved() const { return saved_; }

 private:
  GlStateSnapshot saved_;
};

}  // namespace penumbra::gl
