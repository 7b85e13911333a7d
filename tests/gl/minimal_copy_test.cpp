// The encode's minimal kernel in bench --passes writes every texel of every channel layer, as
// the encode does: a kernel that skipped rows would be timed doing less than the encode and
// flatter its ratio.
#include "minimal_copy.h"

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "gl_formats.h"
#include "gl_test_context.h"
#include "penumbra/channel_layout.h"
#include "penumbra/storage_format.h"
#include "texture_readback.h"

namespace penumbra {
namespace {

class MinimalCopyTest : public testing::GlTest {};

gl::Texture arrayTexture(unsigned format, int size, int layers) {
  gl::Texture t(GL_TEXTURE_2D_ARRAY);
  glTextureStorage3D(t.id(), 1, format, size, size, layers);
  return t;
}

unsigned readFormat(int components) {
  return components == 1 ? GL_RED : components == 2 ? GL_RG : GL_RGBA;
}

// How far a stored value may lie from the sum computed here. 32-bit floats: the shader's product
// and sum round once each, as here, or fused, at most an ulp apart (6e-8 below 1). Normalised
// formats: GL lets a conversion take either neighbouring code (GL 4.5 §2.3.5.2), one step.
float storageTolerance(StorageFormat format) {
  switch (format) {
    case StorageFormat::Float32: return 1e-7f;
    case StorageFormat::Unorm16: return 1.0f / 65535.0f;
    case StorageFormat::Unorm8: return 1.0f / 255.0f;
    case StorageFormat::Float16: break;
  }
  ADD_FAILURE() << "no tolerance for " << storageFormatName(format);
  return 0.0f;
}

TEST_F(MinimalCopyTest, WritesEveryTexelOfEveryLayerFromItsOwnDepth) {
  // 100 texels: not a multiple of a group's 8 x 32 or 8 x 16 texels, so the last groups' rows
  // fall past the edge. ESM (R32F, four rows per invocation), EVSM4 (RGBA32F, two), LVSM (two
  // RGBA16 layers, two rows), CSM (eight RGBA8 layers, two rows: its 1/255 steps are wider than
  // neighbouring texels' depths differ, so it shows which texels and layers are written, the
  // others also which depth).
  const int size = 100;
  for (Technique technique : {Technique::Esm, Technique::Evsm4, Technique::Lvsm, Technique::Csm}) {
    SCOPED_TRACE(std::string(techniqueId(technique)));
    const ChannelLayout layout = channelLayout(technique, defaultTechniqueParams());
    gl::ProgramCache programs;
    const gl::MinimalCopy copy(programs, layout, size);
    // Depths distinct per texel (x + y * size spread over [0, 0.5)), so that a texel written from
    // another texel's depth shows; below 0.5, every value written (at most 0.5 + 7 / 16) stays
    // below the normalised formats' 1.
    std::vector<float> depths(size_t(size) * size);
    for (size_t i = 0; i < depths.size(); ++i) depths[i] = 0.5f * float(i) / float(depths.size());
    gl::Texture depth = arrayTexture(GL_R32F, size, 1);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureSubImage3D(depth.id(), 0, 0, 0, 0, size, size, 1, GL_RED, GL_FLOAT, depths.data());
    gl::Texture channels = arrayTexture(gl::internalFormat(layout), size, layout.layers);
    const float unwritten[4] = {1.0f, 1.0f, 1.0f, 1.0f};  // above every value the copy writes
    glClearTexImage(channels.id(), 0, GL_RGBA, GL_FLOAT, unwritten);
    copy.run(depth, channels);
    glFinish();
    const int components = layout.componentsPerTexel;
    const Image written = gl::readTexture(channels.id(), 0, size, size, layout.layers, components,
                                          readFormat(components), false);
    const float tolerance = storageTolerance(layout.format);
    const float scale[4] = {1.0f, 0.75f, 0.5f, 0.25f};
    int wrong = 0;
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x) {
        const float z = depths[size_t(y) * size + size_t(x)];
        for (int layer = 0; layer < layout.layers; ++layer) {
          for (int k = 0; k < components; ++k) {
            const float expected = z * scale[k] + float(layer) / 16.0f;
            const float got = written.at(x, y, layer * components + k);
            if (std::abs(got - expected) > tolerance && ++wrong <= 5) {
              ADD_FAILURE() << "texel (" << x << ", " << y << ") layer " << layer << " component "
                            << k << ": " << got << ", expected " << expected;
            }
          }
        }
      }
    }
    EXPECT_EQ(wrong, 0);
  }
}

}  // namespace
}  // namespace penumbra
