// The renderer across frames: a warm frame creates and uploads nothing; cascades match the
// filtered reference like one map does; stabilised cascades rasterise a static scene identically
// while the camera creeps.
#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "gl_test_context.h"
#include "gl_wait_counter.h"
#include "penumbra/compare/comparison.h"
#include "penumbra/gl/context.h"
#include "penumbra/gl/renderer.h"
#include "penumbra/metrics.h"
#include "penumbra/scene.h"

namespace penumbra {
namespace {

// Counts calls of the GL entry points that create objects (programs among them: a compile) or
// upload data by swapping libepoxy's dispatch pointers (resolved by the first frame) for
// counting wrappers. Buffer updates of at
// most 4 KiB (`small`) are per-frame parameters like uniforms: the technique block when Lloyd
// moves LVSM's splits, per-cascade blur weights when fitted depth bounds resize the cascades;
// they are counted apart, so a frame whose parameters did not change can be held to none.
struct GlCallCounter {
  static inline int count = 0;
  static inline int small = 0;
  static inline PFNGLCREATETEXTURESPROC createTextures = nullptr;
  static inline PFNGLCREATEBUFFERSPROC createBuffers = nullptr;
  static inline PFNGLNAMEDBUFFERSUBDATAPROC bufferSubData = nullptr;
  static inline PFNGLTEXTURESUBIMAGE3DPROC textureSubImage3D = nullptr;
  static inline PFNGLTEXTURESUBIMAGE2DPROC textureSubImage2D = nullptr;
  static inline PFNGLCREATEPROGRAMPROC createProgram = nullptr;

  GlCallCounter() {
    count = 0;
    small = 0;
    createTextures = epoxy_glCreateTextures;
    createBuffers = epoxy_glCreateBuffers;
    bufferSubData = epoxy_glNamedBufferSubData;
    textureSubImage3D = epoxy_glTextureSubImage3D;
    textureSubImage2D = epoxy_glTextureSubImage2D;
    createProgram = epoxy_glCreateProgram;
    epoxy_glCreateProgram = [] {
      ++count;
      return createProgram();
    };
    epoxy_glCreateTextures = [](GLenum t, GLsizei n, GLuint* ids) {
      ++count;
      createTextures(t, n, ids);
    };
    epoxy_glCreateBuffers = [](GLsizei n, GLuint* ids) {
      ++count;
      createBuffers(n, ids);
    };
    epoxy_glNamedBufferSubData = [](GLuint b, GLintptr o, GLsizeiptr s, const void* d) {
      (s > 4096 ? count : small) += 1;
      bufferSubData(b, o, s, d);
    };
    epoxy_glTextureSubImage3D = [](GLuint t, GLint l, GLint x, GLint y, GLint z, GLsizei w,
                                   GLsizei h, GLsizei d, GLenum f, GLenum ty, const void* p) {
      ++count;
      textureSubImage3D(t, l, x, y, z, w, h, d, f, ty, p);
    };
    epoxy_glTextureSubImage2D = [](GLuint t, GLint l, GLint x, GLint y, GLsizei w, GLsizei h,
                                   GLenum f, GLenum ty, const void* p) {
      ++count;
      textureSubImage2D(t, l, x, y, w, h, f, ty, p);
    };
  }
  ~GlCallCounter() {
    epoxy_glCreateTextures = createTextures;
    epoxy_glCreateBuffers = createBuffers;
    epoxy_glNamedBufferSubData = bufferSubData;
    epoxy_glTextureSubImage3D = textureSubImage3D;
    epoxy_glTextureSubImage2D = textureSubImage2D;
    epoxy_glCreateProgram = createProgram;
  }
};

class FrameRenderer : public testing::GlTest {};

gl::RenderSettings smallSettings(Technique technique) {
  gl::RenderSettings s;
  s.lookupInputs = true;  // the tests read the lookup's inputs
  s.technique = technique;
  s.shadowMapSize = 256;
  s.width = 96;
  s.height = 54;
  return s;
}

TEST_F(FrameRenderer, WarmFrameCreatesAndUploadsNothing) {
  gl::Renderer renderer(*context);
  const Scene scene = makeBuiltinScene("street");
  renderer.setScene(scene);
  struct Case {
    const char* what;
    gl::RenderSettings settings;
    bool parametersChange = false;  // fitted depth resizes cascades; Lloyd moves the splits
  };
  std::vector<Case> cases;
  cases.push_back({"evsm4 trilinear", smallSettings(Technique::Evsm4)});
  cases.push_back({"vsm, 3 stabilised cascades", smallSettings(Technique::Vsm)});
  cases.back().settings.cascades.count = 3;
  cases.push_back({"vsm sat, 3 cascades fitted to depth", smallSettings(Technique::Vsm), true});
  cases.back().settings.filter = FilterMode::SummedArea;
  cases.back().settings.cascades.count = 3;
  cases.back().settings.cascades.fitDepthBounds = true;
  cases.push_back({"esm zmax", smallSettings(Technique::Esm)});
  cases.back().settings.params.esm.classifier = shaders::kEsmClassifyZmax;
  cases.push_back({"lvsm lloyd, 2 cascades", smallSettings(Technique::Lvsm), true});
  cases.back().settings.params.lvsm.placement = shaders::kLayerPlacementLloyd;
  cases.back().settings.cascades.count = 2;
  // Fitted depth bounds resize the cascades with the view, and with them each cascade's
  // Gaussian (here cascade 1's sigma 0.452 -> 0.446): its weights are uniforms, not a program
  // per frame (the radius, compiled in, moves in whole taps only).
  cases.push_back(
      {"evsm4 fused, Gaussian, 3 cascades fitted to depth", smallSettings(Technique::Evsm4), true});
  cases.back().settings.cascades.count = 3;
  cases.back().settings.cascades.fitDepthBounds = true;
  cases.back().settings.fusePrefilter = true;
  for (const Case& c : cases) {
    gl::FrameView view{scene.camera, scene.light};
    renderer.render(c.settings, view);  // cold: creates the pass resources
    GlCallCounter counter;
    view.camera.position.x += 0.2f;  // a new view: nothing to re-create
    view.light.direction = glm::normalize(view.light.direction + glm::vec3(0.0f, 0.0f, 0.05f));
    renderer.render(c.settings, view);
    EXPECT_EQ(GlCallCounter::count, 0) << c.what << ": GL objects created or data uploaded";
    if (!c.parametersChange) {
      EXPECT_EQ(GlCallCounter::small, 0) << c.what << ": parameters re-uploaded unchanged";
    }
  }
  // The counter sees real work: a new size re-creates the light pass and the channels.
  GlCallCounter counter;
  gl::RenderSettings bigger = cases[0].settings;
  bigger.shadowMapSize = 512;
  renderer.render(bigger, gl::FrameView{scene.camera, scene.light});
  EXPECT_GT(GlCallCounter::count, 0);
}

// A frame that reads nothing back and is not timed waits for nothing (RenderSettings::readBack),
// LVSM's Lloyd placement included: its splits stay on the GPU, and the result says so (NaN); a
// frame that reads an image back reads them too, the same splits.
TEST_F(FrameRenderer, AFrameThatReadsNothingBackWaitsForNothing) {
  gl::Renderer renderer(*context);
  const Scene scene = makeBuiltinScene("backyard");
  renderer.setScene(scene);
  gl::RenderSettings s = smallSettings(Technique::Lvsm);
  s.lookupInputs = false;
  s.params.lvsm.placement = shaders::kLayerPlacementLloyd;
  s.cascades.count = 2;
  const gl::FrameView view{scene.camera, scene.light};
  const gl::RenderResult read = renderer.render(s, view);  // compiles and creates everything
  s.timing = false;
  // Nothing asked, and the lookup's inputs asked of a frame that does not write them.
  for (const unsigned readBack : {gl::frame_image::kNone, gl::frame_image::kLookup}) {
    s.readBack = readBack;
    gl::RenderResult unread;
    {
      const testing::WaitCounter counter;
      unread = renderer.render(s, view);
      EXPECT_EQ(testing::WaitCounter::waits, 0) << readBack;
    }
    for (int i = 1; i < s.params.lvsm.splits.layerCount; ++i) {
      EXPECT_TRUE(std::isnan(shaders::layerSplit(unread.params.lvsm.splits, i))) << i;
      const float placed = shaders::layerSplit(read.params.lvsm.splits, i);
      EXPECT_GT(placed, 0.0f) << i;
      EXPECT_LT(placed, 1.0f) << i;
    }
  }
  s.readBack = gl::frame_image::kColor;
  const gl::RenderResult again = renderer.render(s, view);
  for (int i = 1; i < s.params.lvsm.splits.layerCount; ++i) {
    EXPECT_EQ(shaders::layerSplit(again.params.lvsm.splits, i),
              shaders::layerSplit(read.params.lvsm.splits, i))
        << "the same view places the same splits";
  }
}

// Cascades fitted to the visible depths (--cascade-depth fitted): a frame that reads nothing back
// and is not timed takes the previous frame's bounds and, the GPU done with them, waits for
// nothing; a frame that reads an image takes its own; a first measurement, and the first after
// a new scene, waits for its own.
TEST_F(FrameRenderer, FittedDepthBoundsWaitOnlyInAFrameThatReadsBack) {
  const Scene scene = makeBuiltinScene("backyard");
  gl::RenderSettings s = smallSettings(Technique::Vsm);
  s.lookupInputs = false;
  s.cascades.count = 2;
  s.cascades.fitDepthBounds = true;
  // Three views that see different depths.
  std::vector<gl::FrameView> views;
  for (const float closer : {0.0f, 0.6f, 0.3f}) {
    Camera camera = scene.camera;
    camera.position = glm::mix(scene.camera.position, scene.camera.target, closer);
    views.push_back({camera, scene.light});
  }
  const auto same = [](DepthRange a, DepthRange b) { return a.near == b.near && a.far == b.far; };

  gl::Renderer renderer(*context);
  renderer.setScene(scene);
  s.readBack = gl::frame_image::kColor;
  std::vector<DepthRange> own;
  for (const gl::FrameView& view : views) own.push_back(renderer.render(s, view).depthBounds);
  ASSERT_FALSE(same(own[0], own[1]) || same(own[1], own[2]) || same(own[0], own[2]))
      << "the views must see different depths for this to tell their bounds apart";

  s.readBack = gl::frame_image::kNone;
  s.timing = false;
  int previous = 2;
  for (const int view : {0, 1, 2, 1}) {
    glFinish();  // the previous frame's bounds are done on any GPU
    const testing::WaitCounter counter;
    const gl::RenderResult unread = renderer.render(s, views[size_t(view)]);
    EXPECT_EQ(testing::WaitCounter::waits, 0) << view;
    EXPECT_TRUE(same(unread.depthBounds, own[size_t(previous)]))
        << "view " << view << " takes view " << previous << "'s bounds";
    previous = view;
  }
  s.readBack = gl::frame_image::kColor;
  EXPECT_TRUE(same(renderer.render(s, views[0]).depthBounds, own[0]))
      << "a frame that reads back takes its own bounds";

  // A new scene's first frame: no bounds of the backyard's, its own after a wait.
  const Scene other = makeBuiltinScene("planar");
  s.readBack = gl::frame_image::kColor;
  const DepthRange otherOwn = renderer.render(other, s).depthBounds;
  renderer.setScene(scene);
  s.readBack = gl::frame_image::kNone;
  {
    const testing::WaitCounter counter;
    EXPECT_TRUE(same(renderer.render(s, views[1]).depthBounds, own[1]))
        << "a first measurement waits for its own";
    // Its fence asked for (a poll where llvmpipe is done: it runs the reduction at dispatch):
    // the counter sees these calls, and the frames above asked for none that waited.
    EXPECT_GE(testing::WaitCounter::waits + testing::WaitCounter::polls, 1);
  }
  EXPECT_FALSE(same(otherOwn, own[1]));
}

TEST_F(FrameRenderer, EveryCascadeOfAPlanarSceneMatchesTheFilteredReference) {
  // VSM is exact for a planar occluder over a parallel planar receiver (thesis §3.2), so each
  // cascade's pixels must match the filtered reference as closely as one map's do.
  gl::Renderer renderer(*context);
  const Scene scene = makeBuiltinScene("planar");
  gl::RenderSettings s = smallSettings(Technique::Vsm);
  s.width = 192;
  s.height = 108;
  s.filter = FilterMode::Bilinear;
  s.cascades.count = 4;
  s.cascades.fitDepthBounds = true;  // the visible ground, about 5 to 10 m from the camera
  const gl::RenderResult r = renderer.render(scene, s);
  const gl::RenderResult ref = renderer.renderReference(scene, s, 1);
  std::vector<double> sum(4, 0.0);
  std::vector<int> pixels(4, 0);
  for (int y = 0; y < s.height; ++y) {
    for (int x = 0; x < s.width; ++x) {
      const int c = int(r.cascades.at(x, y, 0));
      if (c < 0 || r.lookup.at(x, y, 3) < 1.0f) continue;
      ASSERT_EQ(int(ref.cascades.at(x, y, 0)), c) << "the reference uses the pixel's cascade";
      const double d = r.visibility.at(x, y) - ref.visibility.at(x, y);
      sum[size_t(c)] += d * d;
      ++pixels[size_t(c)];
    }
  }
  for (int c = 0; c < 4; ++c) {
    ASSERT_GT(pixels[size_t(c)], 100) << "cascade " << c << " must cover part of the frame";
    // The single-map bound of the planar test (renderer_test.cpp): fp32 moments and bilinear
    // weights leave RMSE well below 1e-3.
    EXPECT_LT(std::sqrt(sum[size_t(c)] / pixels[size_t(c)]), 1e-3) << "cascade " << c;
  }
}

TEST_F(FrameRenderer, PcfKeepsItsKernelsWorldWidthInEveryCascade) {
  // PCF with the prefilter's kernel is the filtered reference itself for bilinear lookups
  // (compare's matched PCF); the reference widens the kernel per cascade to a constant world
  // width, so PCF must too, or every cascade beyond the first filters a different region.
  gl::Renderer renderer(*context);
  const Scene scene = makeBuiltinScene("street");
  gl::RenderSettings s = smallSettings(Technique::Pcf);
  s.width = 192;
  s.height = 108;
  s.filter = FilterMode::Bilinear;
  s.blur = {BlurKernel::Box, 4, 1.0f};  // 9 taps in cascade 0, fewer farther out
  s.cascades.count = 2;
  s.cascades.distances = {15.0f};  // the second cascade from 15 m: much of the street
  s.params.pcf = compare::pcfMatchingPrefilter(s);
  const gl::RenderResult r = renderer.render(scene, s);
  const gl::RenderResult ref = renderer.renderReference(scene, s, 1);
  ASSERT_LT(r.cascadeBlurs[1].radius, s.blur.radius) << "the far cascade's kernel is narrower";
  std::vector<double> worst(2, 0.0);
  std::vector<int> pixels(2, 0);
  for (int y = 0; y < s.height; ++y) {
    for (int x = 0; x < s.width; ++x) {
      const int c = int(r.cascades.at(x, y, 0));
      if (c < 0 || r.lookup.at(x, y, 3) < 1.0f) continue;  // blend bands too
      worst[size_t(c)] = std::max(
          worst[size_t(c)], double(std::abs(r.visibility.at(x, y) - ref.visibility.at(x, y))));
      ++pixels[size_t(c)];
    }
  }
  for (int c = 0; c < 2; ++c) {
    ASSERT_GT(pixels[size_t(c)], 100) << "cascade " << c << " must cover part of the frame";
    // Both sum the same taps with fp32 weights in the same order (renderer_test's PCF bound).
    EXPECT_LT(worst[size_t(c)], 1e-5) << "cascade " << c;
  }
}

TEST_F(FrameRenderer, StabilizedCascadesRasteriseAStaticSceneIdenticallyAsTheCameraCreeps) {
  gl::Renderer renderer(*context);
  const Scene scene = makeBuiltinScene("street");
  renderer.setScene(scene);
  for (CascadeFit fit : {CascadeFit::Stabilized, CascadeFit::Tight}) {
    gl::RenderSettings s = smallSettings(Technique::Hard);
    s.cascades.count = 3;
    s.cascades.fit = fit;
    gl::FrameView view{scene.camera, scene.light};
    const gl::RenderResult first = renderer.render(s, view);
    std::vector<Image> maps;
    for (int c = 0; c < 3; ++c) maps.push_back(renderer.readDepthMap(c));
    // A hundredth of cascade 0's texel sideways and forward, and a slight turn.
    const float step = 0.01f * first.cascadeFrame.texelWorldSize(0, s.shadowMapSize);
    view.camera.position += glm::vec3(step, 0.0f, -step);
    view.camera.target += glm::vec3(2.0f * step, 0.0f, -step);
    const gl::RenderResult moved = renderer.render(s, view);
    int identical = 0;
    for (int c = 0; c < 3; ++c) {
      const Image now = renderer.readDepthMap(c);
      const Image& before = maps[size_t(c)];
      identical += std::equal(now.data().begin(), now.data().end(), before.data().begin());
      if (fit != CascadeFit::Stabilized) continue;
      const glm::vec4 a = first.cascadeFrame.boxes[size_t(c)];
      const glm::vec4 b = moved.cascadeFrame.boxes[size_t(c)];
      EXPECT_EQ(a.z, b.z) << "cascade " << c << ": a stabilised box keeps its size";
      // The box moves by whole texels (usually none): the same world point sits `shift` texels
      // lower in the new map, so now(i) == before(i + shift) wherever both hold it.
      const float texel = a.z / float(s.shadowMapSize);
      const glm::vec2 shiftTexels = (glm::vec2(b) - glm::vec2(a)) / texel;
      const glm::ivec2 shift(glm::round(shiftTexels));
      ASSERT_LT(glm::length(shiftTexels - glm::vec2(shift)), 1e-3f) << "cascade " << c;
      int mismatches = 0;
      for (int y = 0; y < s.shadowMapSize; ++y) {
        for (int x = 0; x < s.shadowMapSize; ++x) {
          const int sx = x + shift.x, sy = y + shift.y;
          if (sx < 0 || sy < 0 || sx >= s.shadowMapSize || sy >= s.shadowMapSize) continue;
          mismatches += now.at(x, y) != before.at(sx, sy);
        }
      }
      EXPECT_EQ(mismatches, 0) << "cascade " << c
                               << ": a stabilised map of a static scene is "
                                  "the same rasterisation, shifted by "
                               << shift.x << ", " << shift.y << " texels";
    }
    if (fit == CascadeFit::Tight) {
      EXPECT_EQ(identical, 0) << "tight boxes follow the camera: every map changes";
    }
  }
}

TEST_F(FrameRenderer, StabilisedCascadesShimmerLessAlongTheCameraPath) {
  // The cascades follow the street's camera path (sub-pixel steps down the street) while the view
  // holds still at its first camera, so the picture changes only where the shadow maps do.
  // Tight boxes follow the camera and resample the shadow edges every frame; stabilised boxes
  // keep their texel grid.
  gl::Renderer renderer(*context);
  const Scene scene = makeBuiltinScene("street");
  renderer.setScene(scene);
  const std::vector<Camera> path = scene.cameraPath(5);
  double shimmer[2] = {0.0, 0.0};
  for (CascadeFit fit : {CascadeFit::Stabilized, CascadeFit::Tight}) {
    gl::RenderSettings s = smallSettings(Technique::Hard);
    s.width = 192;
    s.height = 108;
    s.cascades.count = 3;
    s.cascades.fit = fit;
    std::vector<Image> visibilities, masks;
    for (const Camera& camera : path) {
      const gl::RenderResult r = renderer.render(s, gl::FrameView{path[0], scene.light, camera});
      visibilities.push_back(r.visibility);
      masks.push_back(litSurfaceMask(r.lookup));
    }
    shimmer[fit == CascadeFit::Tight] = frameToFrameChange(visibilities, masks);
  }
  RecordProperty("shimmer_stabilized", std::to_string(shimmer[0]));
  RecordProperty("shimmer_tight", std::to_string(shimmer[1]));
  EXPECT_LT(shimmer[0], 0.5 * shimmer[1])
      << "stabilised " << shimmer[0] << ", tight " << shimmer[1];
}

}  // namespace
}  // namespace penumbra
