// ShadowFilter, the filtering API over a host's own depth texture: what it imports, what a
// host's shader samples through the installed (amalgamated) GLSL with its own bindings, the
// state it leaves, and the inputs it refuses.
#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <sstream>

#include "gl_state.h"
#include "gl_test_context.h"
#include "penumbra/error.h"
#include "penumbra/gl/program.h"
#include "penumbra/gl/renderer.h"
#include "penumbra/gl/shadow_filter.h"
#include "shadow_filter_state.h"

namespace penumbra::gl {
namespace {

using penumbra::testing::GlTest;

// A host's depth texture: GL_DEPTH_COMPONENT32F, `size` square, filled column by column.
struct HostDepth {
  Texture texture{GL_TEXTURE_2D};
  int size = 0;
  HostDepth(int n, const std::vector<float>& windowDepth) : size(n) {
    glTextureStorage2D(texture.id(), 1, GL_DEPTH_COMPONENT32F, n, n);
    glTextureSubImage2D(texture.id(), 0, 0, 0, n, n, GL_DEPTH_COMPONENT, GL_FLOAT,
                        windowDepth.data());
    // A host sampling it with sampler2DShadow has comparison on: the filter must read texels.
    glTextureParameteri(texture.id(), GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  }
  DepthInput input() const {
    DepthInput d;
    d.texture = texture.id();
    d.size = size;
    return d;
  }
};

// Left half an occluder at window depth 0.3, right half nothing (the far plane).
std::vector<float> halfOccluded(int n) {
  std::vector<float> depth(size_t(n) * size_t(n));
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) depth[size_t(y * n + x)] = x < n / 2 ? 0.3f : 1.0f;
  }
  return depth;
}

std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The hard test's filter of `input` (nothing but the import and a copy), and the linear depth
// it imported, layer 0.
std::vector<float> importedDepth(ShadowFilter& filter, const DepthInput& input) {
  FilterSettings settings;
  settings.technique = Technique::Hard;
  filter.filter(input, settings);
  std::vector<float> linear(size_t(input.size) * size_t(input.size) * size_t(input.layers));
  glGetTextureImage(filter.linearDepthTexture(), 0, GL_RED, GL_FLOAT,
                    GLsizei(linear.size() * sizeof(float)), linear.data());
  return linear;
}

// Bindings a host with its own resources on the low units might choose.
ShadowBindings movedBindings() {
  ShadowBindings b;
  b.channelUnit = 5;
  b.zmaxUnit = 6;
  b.depthUnit = 7;
  b.parameterBlock = 3;
  b.layerRangeBlock = 4;
  b.lookupBlock = 5;
  b.satStatsBuffer = 6;
  b.satSumsBuffer = 7;
  b.blurWeightsBuffer = 8;
  return b;
}

// The host's shader: its own #version, the filter's preamble, the installed amalgamated file
// for the technique, then its code: visibility at the given shadow coordinates.
std::vector<float> sampleAsHost(const ShadowFilter& filter, Technique technique,
                                const ShadowBindings& bindings,
                                const std::vector<glm::vec4>& coords) {
  const std::string glsl = readText(std::string(PENUMBRA_GLSL_BUILD_DIR) + "/penumbra_" +
                                    std::string(techniqueId(technique)) + ".glsl");
  EXPECT_FALSE(glsl.empty());
  ShaderLibrary library;
  library.addFile("host/probe.comp",
                  "#define PENUMBRA_NO_DERIVATIVES 1\n" + filter.shaderPreamble(bindings) + glsl +
                      "layout(local_size_x = 1) in;\n"
                      "layout(std430, binding = 9) buffer Io { vec4 io[]; };\n"
                      "void main() {\n"
                      "  uint i = gl_GlobalInvocationID.x;\n"
                      "  io[i].w = penumbraShadow(int(io[i].w), io[i].xyz, vec2(0.0f),\n"
                      "                           vec2(0.0f), vec2(0.0f));\n"
                      "}\n");
  const Program program = Program::compute(library, "host/probe.comp");
  // (u, v, window depth, layer) in, visibility out in w.
  std::vector<glm::vec4> io = coords;
  Buffer buffer(std::as_bytes(std::span(io)));
  buffer.bindStorage(9);
  filter.bind(bindings);
  program.dispatch(unsigned(io.size()));
  buffer.read(std::as_writable_bytes(std::span(io)));
  std::vector<float> visibility;
  for (const glm::vec4& v : io) visibility.push_back(v.w);
  return visibility;
}

TEST_F(GlTest, ShadowFilterHostShaderSeesOccluderThroughEveryTechnique) {
  const int n = 64;
  HostDepth depth(n, halfOccluded(n));
  ShadowFilter filter;
  for (Technique t : allTechniques()) {
    SCOPED_TRACE(std::string(techniqueId(t)));
    FilterSettings settings;
    settings.technique = t;
    filter.filter(depth.input(), settings);
    // Receivers at window depth 0.7, a quarter of the map from the edge (the 5-tap kernel
    // reaches 2 texels): behind the occluder on the left, in front of nothing on the right.
    const std::vector<float> v = sampleAsHost(
        filter, t, movedBindings(), {{0.25f, 0.5f, 0.7f, 0.0f}, {0.75f, 0.5f, 0.7f, 0.0f}});
    // Each technique's error at a lone step 0.4 deep is well under 0.05 (ESM: exp(-80 * 0.4),
    // moments: no variance, CSM: its ringing at that distance); 0.05 still tells 0 from 1.
    EXPECT_LT(v[0], 0.05f);
    EXPECT_GT(v[1], 0.95f);
    // PCF and the hard test filter the depth after the test: no channel texture is made (and no
    // encode copies the depth into one); the others' channels are 64^2 texels of 4+ bytes.
    if (prefiltersChannels(t)) {
      EXPECT_NE(filter.channelTexture(), 0u);
      EXPECT_GE(filter.memory().channels, uint64_t(n * n * 4));
    } else {
      EXPECT_EQ(filter.channelTexture(), 0u);
      EXPECT_EQ(filter.memory().channels, 0u);
    }
  }
}

TEST_F(GlTest, ShadowFilterMatchesTheRendererBitForBit) {
  // The renderer's own path (linear depth, used as it is) and a host's D32F window depth of
  // an orthographic light (imported) must give the same channels: the import copies exactly.
  const int n = 64;
  std::vector<float> values(size_t(n) * size_t(n));
  for (int i = 0; i < n * n; ++i) values[size_t(i)] = 0.2f + 0.6f * float((i * 37) % 101) / 101.0f;
  Image image(n, n, 1);
  std::copy(values.begin(), values.end(), image.data().begin());
  Renderer renderer(*context);
  RenderSettings rs;
  rs.technique = Technique::Msm;
  rs.blur = {BlurKernel::Box, 2, 1.0f};
  rs.filter = FilterMode::Bilinear;
  renderer.filterDepthMap(image, rs);
  const Image expected = renderer.readChannels(0);

  HostDepth depth(n, values);
  ShadowFilter filter;
  FilterSettings settings;
  settings.technique = Technique::Msm;
  settings.blur = rs.blur;
  settings.filter = rs.filter;
  filter.filter(depth.input(), settings);
  const ChannelShape& shape = filter.state().maps.shape();
  std::vector<float> got(size_t(n) * size_t(n) * 4);
  ASSERT_EQ(filter.channelTexture(), filter.state().maps.channels().id());
  glGetTextureImage(filter.channelTexture(), 0, GL_RGBA, GL_FLOAT,
                    GLsizei(got.size() * sizeof(float)), got.data());
  ASSERT_EQ(shape.layout.channels, 4);
  int differing = 0;
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      for (int c = 0; c < 4; ++c) {
        differing += got[size_t((y * n + x) * 4 + c)] != expected.at(x, y, c);
      }
    }
  }
  EXPECT_EQ(differing, 0);
}

TEST_F(GlTest, ShadowFilterLinearisesPerspectiveWindowDepth) {
  // A spot light's projection (near 1, far 11) puts a surface 6 units down its axis at
  // hyperbolic window depth; penumbra's metric is (6 - 1) / (11 - 1) = 0.5 there.
  const float nearDistance = 1.0f, farDistance = 11.0f;
  const glm::mat4 projection =
      glm::perspective(glm::radians(60.0f), 1.0f, nearDistance, farDistance);
  const glm::vec4 clip = projection * glm::vec4(0.0f, 0.0f, -6.0f, 1.0f);
  const float window = clip.z / clip.w * 0.5f + 0.5f;
  const int n = 16;
  HostDepth depth(n, std::vector<float>(size_t(n * n), window));
  DepthInput input = depth.input();
  input.perspective = true;
  input.nearDistance = nearDistance;
  input.farDistance = farDistance;
  ShadowFilter filter;
  const std::vector<float> linear = importedDepth(filter, input);
  // fp32 window depth near 0.9 resolves 6e-8; the inverse map's slope there is z^2/(n f)
  // (about 3.3) over (f - n): a few 1e-8 in the metric, 1e-6 leaves room for the division.
  EXPECT_EQ(filter.memory().importedDepth, uint64_t(n * n * 4));  // the R32F copy, reported
  EXPECT_NEAR(linear[0], 0.5f, 1e-6f);
  EXPECT_NEAR(linear[size_t(n * n - 1)], 0.5f, 1e-6f);
  // A receiver 5.9 units down the axis is in front of that surface, one at 6.1 behind it:
  // the host's shadowCoord.z is its own window depth, linearised the same way.
  auto windowAt = [&](float z) {
    const glm::vec4 c = projection * glm::vec4(0.0f, 0.0f, -z, 1.0f);
    return c.z / c.w * 0.5f + 0.5f;
  };
  const std::vector<float> v =
      sampleAsHost(filter, Technique::Hard, ShadowBindings{},
                   {{0.5f, 0.5f, windowAt(5.9f), 0.0f}, {0.5f, 0.5f, windowAt(6.1f), 0.0f}});
  EXPECT_EQ(v[0], 1.0f);
  EXPECT_EQ(v[1], 0.0f);
}

// Host state a guest must not disturb: non-default everywhere penumbra's passes reach.
struct HostState {
  Texture textures[4] = {Texture(GL_TEXTURE_2D), Texture(GL_TEXTURE_2D), Texture(GL_TEXTURE_2D),
                         Texture(GL_TEXTURE_2D_ARRAY)};
  Buffer buffer{256};
  GLuint vao = 0, framebuffer = 0;
  HostState() {
    for (int i = 0; i < 3; ++i) glTextureStorage2D(textures[i].id(), 1, GL_RGBA8, 4, 4);
    glTextureStorage3D(textures[3].id(), 1, GL_R32F, 4, 4, 2);
    for (unsigned unit = 0; unit < 3; ++unit) glBindTextureUnit(unit, textures[unit].id());
    glBindTextureUnit(4, textures[3].id());
    glBindImageTexture(0, textures[0].id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA8);
    glBindBufferRange(GL_UNIFORM_BUFFER, 0, buffer.id(), 0, 64);
    glBindBufferRange(GL_UNIFORM_BUFFER, 2, buffer.id(), 0, 128);
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 1, buffer.id(), 0, 128);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, buffer.id());
    glCreateVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glCreateFramebuffers(1, &framebuffer);
    glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, textures[1].id(), 0);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glViewport(1, 2, 3, 4);
    glEnable(GL_BLEND);
    glEnable(GL_CULL_FACE);
    glDisable(GL_DEPTH_TEST);
    glActiveTexture(GL_TEXTURE3);
  }
  ~HostState() {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &framebuffer);
    glBindVertexArray(0);
    glDeleteVertexArrays(1, &vao);
    glActiveTexture(GL_TEXTURE0);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
  }
};

TEST_F(GlTest, ShadowFilterLeavesTheHostsStateAsItWas) {
  HostDepth depth(64, halfOccluded(64));
  HostState host;
  ShadowFilter filter;
  struct Case {
    Technique technique;
    FilterMode mode;
    const char* param;
  };
  // Every pass: import, encode, fused and separate blur, mips, the summed-area table, ESM's
  // Z-max pyramid, LVSM's Lloyd placement.
  for (auto [technique, mode, fused] :
       {std::tuple{Technique::Hard, FilterMode::Bilinear, true},
        std::tuple{Technique::Vsm, FilterMode::Trilinear, true},
        std::tuple{Technique::Evsm4, FilterMode::Trilinear, false},
        std::tuple{Technique::Esm, FilterMode::Bilinear, true},
        std::tuple{Technique::Msm, FilterMode::SummedArea, false},
        std::tuple{Technique::Lvsm, FilterMode::Trilinear, true},
        std::tuple{Technique::PowerCdf, FilterMode::Trilinear, true}}) {
    SCOPED_TRACE(std::string(techniqueId(technique)));
    FilterSettings settings;
    settings.technique = technique;
    settings.filter = mode;
    settings.fusePrefilter = fused;
    settings.params.esm.classifier = shaders::kEsmClassifyZmax;
    settings.params.lvsm.placement = shaders::kLayerPlacementLloyd;
    const GlStateSnapshot before = GlStateSnapshot::capture(16);
    filter.filter(depth.input(), settings);
    const GlStateSnapshot after = GlStateSnapshot::capture(16);
    EXPECT_TRUE(before == after) << before.differences(after);
  }
}

TEST_F(GlTest, ShadowFilterRebindsNothingItDeleted) {
  // A host binds the map, then the next frame's map has another size: the old textures are
  // gone, and restoring the host's bindings must not name them (GL_INVALID_OPERATION).
  ShadowFilter filter;
  FilterSettings settings;
  settings.technique = Technique::Vsm;
  settings.filter = FilterMode::Trilinear;
  HostDepth small(32, halfOccluded(32)), large(64, halfOccluded(64));
  filter.filter(small.input(), settings);
  filter.bind();
  filter.filter(large.input(), settings);
  EXPECT_NO_THROW(checkErrors("filtering after the host bound the last map"));
}

TEST_F(GlTest, ShadowFilterRefusesInputsItCannotRead) {
  ShadowFilter filter;
  const FilterSettings settings;
  Texture colour(GL_TEXTURE_2D);
  glTextureStorage2D(colour.id(), 1, GL_RGBA8, 32, 32);
  DepthInput d;
  d.texture = colour.id();
  d.size = 32;
  auto message = [&](const DepthInput& input) {
    try {
      filter.filter(input, settings);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(d).find("depth-format texture"), std::string::npos) << message(d);
  HostDepth depth(32, halfOccluded(32));
  DepthInput wrongSize = depth.input();
  wrongSize.size = 64;
  EXPECT_NE(message(wrongSize).find("is 32x32"), std::string::npos) << message(wrongSize);
  DepthInput none;
  none.size = 32;
  EXPECT_NE(message(none).find("not a GL texture"), std::string::npos) << message(none);
  DepthInput reversed = depth.input();
  reversed.perspective = true;
  reversed.nearDistance = 0.0f;
  EXPECT_NE(message(reversed).find("near > 0"), std::string::npos) << message(reversed);
}

TEST_F(GlTest, ShadowFilterReadsEveryLayerOfAnArray) {
  // Three cascades (or faces) in one D32F array, each at its own depth: the import converts
  // every layer and the host's lookup reads the layer it names.
  const int n = 32;
  Texture array(GL_TEXTURE_2D_ARRAY);
  glTextureStorage3D(array.id(), 1, GL_DEPTH_COMPONENT32F, n, n, 3);
  const float layerDepth[3] = {0.2f, 0.5f, 0.8f};
  for (int layer = 0; layer < 3; ++layer) {
    const std::vector<float> values(size_t(n * n), layerDepth[layer]);
    glTextureSubImage3D(array.id(), 0, 0, 0, layer, n, n, 1, GL_DEPTH_COMPONENT, GL_FLOAT,
                        values.data());
  }
  DepthInput input;
  input.texture = array.id();
  input.size = n;
  input.layers = 3;
  ShadowFilter filter;
  FilterSettings settings;
  settings.technique = Technique::Hard;
  filter.filter(input, settings);
  // A receiver at 0.65 is behind layers 0 and 1, in front of layer 2.
  const std::vector<float> v = sampleAsHost(
      filter, Technique::Hard, ShadowBindings{},
      {{0.5f, 0.5f, 0.65f, 0.0f}, {0.5f, 0.5f, 0.65f, 1.0f}, {0.5f, 0.5f, 0.65f, 2.0f}});
  EXPECT_EQ(v[0], 0.0f);
  EXPECT_EQ(v[1], 0.0f);
  EXPECT_EQ(v[2], 1.0f);
}

TEST_F(GlTest, ShadowFilterReadsDepthOfADepthStencilTextureSampledAsStencil) {
  // A host that samples its D24S8 map's stencil has set GL_STENCIL_INDEX: the import must read
  // depth anyway, and give the host its mode back.
  const int n = 16;
  Texture depthStencil(GL_TEXTURE_2D);
  glTextureStorage2D(depthStencil.id(), 1, GL_DEPTH24_STENCIL8, n, n);
  // 24-bit depth 0.5 (0x800000 / 0xffffff) above an 8-bit stencil of 0xff.
  const std::vector<uint32_t> packed(size_t(n * n), (0x800000u << 8) | 0xffu);
  glTextureSubImage2D(depthStencil.id(), 0, 0, 0, n, n, GL_DEPTH_STENCIL, GL_UNSIGNED_INT_24_8,
                      packed.data());
  glTextureParameteri(depthStencil.id(), GL_DEPTH_STENCIL_TEXTURE_MODE, GL_STENCIL_INDEX);
  DepthInput input;
  input.texture = depthStencil.id();
  input.size = n;
  ShadowFilter filter;
  const std::vector<float> linear = importedDepth(filter, input);
  // 0x800000 / 0xffffff, exact in fp32 to well under 1e-6 (stencil 255 would read as 255).
  EXPECT_NEAR(linear[0], 8388608.0f / 16777215.0f, 1e-6f);
  GLint mode = 0;
  glGetTextureParameteriv(depthStencil.id(), GL_DEPTH_STENCIL_TEXTURE_MODE, &mode);
  EXPECT_EQ(mode, GL_STENCIL_INDEX);
}

TEST_F(GlTest, ShadowFilterRefusesSettingsAndBindingsItCannotServe) {
  ShadowFilter filter;
  auto message = [](auto&& call) {
    try {
      call();
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message([&] { (void)filter.shaderPreamble(); }).find("nothing filtered yet"),
            std::string::npos);
  HostDepth depth(32, halfOccluded(32));
  // ESM's exponentials do not survive the table's fixed point: the renderer refuses it, so
  // must the filter (the same check).
  FilterSettings esmSat;
  esmSat.technique = Technique::Esm;
  esmSat.filter = FilterMode::SummedArea;
  const std::string sat = message([&] { filter.filter(depth.input(), esmSat); });
  EXPECT_NE(sat.find("summed-area"), std::string::npos) << sat;

  FilterSettings vsm;
  filter.filter(depth.input(), vsm);
  ShadowBindings shared;
  shared.depthUnit = shared.channelUnit;
  const std::string same = message([&] { filter.bind(shared); });
  EXPECT_NE(same.find("two texture units share binding 0"), std::string::npos) << same;
  ShadowBindings negative;
  negative.lookupBlock = -1;
  const std::string range = message([&] { (void)filter.shaderPreamble(negative); });
  EXPECT_NE(range.find("lookupBlock -1 is out of range"), std::string::npos) << range;

  Texture multisampled(GL_TEXTURE_2D_MULTISAMPLE_ARRAY);
  glTextureStorage3DMultisample(multisampled.id(), 2, GL_R32F, 32, 32, 1, GL_TRUE);
  GLint given = 0;  // at least the 2 asked for (llvmpipe gives 4)
  glGetTextureLevelParameteriv(multisampled.id(), 0, GL_TEXTURE_SAMPLES, &given);
  DepthInput msaa;
  msaa.texture = multisampled.id();
  msaa.size = 32;
  msaa.samples = given * 2;
  msaa.encoding = DepthEncoding::LinearDepth;
  const std::string samples = message([&] { filter.filter(msaa, vsm); });
  EXPECT_NE(samples.find("has " + std::to_string(given) + " samples; the input says " +
                         std::to_string(given * 2)),
            std::string::npos)
      << samples;
}

}  // namespace
}  // namespace penumbra::gl
