// The camera pass: the scene from the camera, each pixel's shadow lookup in its cascade (or the
// filtered reference), shading, and the lookup's inputs as extra targets for the CPU twin. Owns
// its render targets and keeps them while the frame size stays the same.
#pragma once

#include <span>

#include "gpu_scene.h"
#include "gpu_timer.h"
#include "penumbra/cascades.h"
#include "penumbra/filters.h"
#include "penumbra/gl/program.h"
#include "penumbra/gl/renderer.h"
#include "penumbra/gl/shadow_filter.h"
#include "program_cache.h"

namespace penumbra::gl {

// The frame's geometry: camera, light and the cascades (one map: count 1 with an identity box).
struct FrameGeometry {
  Camera camera;
  Camera shadowCamera;  // the cascades' (FrameView::shadowCamera): its view depth selects them
  Light light;
  ViewBounds viewBounds;
  LightView lightView;  // the light's view and depth metric (one map: also its projection)
  bool cascaded = false;
  // A point light: the cascades are its six faces (penumbra/point_light.h), chosen per pixel by
  // face; lightView.clipFromLight is every face's guarded projection.
  bool pointLight = false;
  float pointFaceTangent = 1.0f;
  CascadeFrame cascades;
  int shadowMapSize = 0;
};

class CameraPass {
 public:
  CameraPass() = default;
  ~CameraPass();
  CameraPass(const CameraPass&) = delete;
  CameraPass& operator=(const CameraPass&) = delete;

  // diagnostics: also the visibility and diagnostic targets (writesDiagnostics); lookupInputs:
  // also the four targets of the lookup's inputs (RenderSettings::lookupInputs), and the
  // diagnostics' (their locations come first). render() writes the targets prepared.
  void prepare(int width, int height, bool diagnostics, bool lookupInputs);
  // The shadow maps are the filter's last filter() (or prepareRawDepth() for the reference).
  void render(ProgramCache& programs, const GpuScene& scene, const RenderSettings& settings,
              const FrameGeometry& frame, const ShadowFilter& shadows, bool reference);

  // Row 0 at the top.
  Image readColor() const;
  // Only after prepare(..., diagnostics or lookupInputs = true).
  Image readVisibility() const;
  Image readDiagnostic() const;
  // The lookup's inputs: only after prepare(..., lookupInputs = true).
  Image readLookup() const;
  Image readReceiverPlane() const;
  Image readUvDerivatives() const;
  Image readCascades() const;
  Image readDepth() const;  // window depth in [0,1], 1 where nothing is drawn
  uint64_t bytes() const;   // frameBytes of the targets prepared: what the estimate counts
  // The targets' bytes as the GL reports their sizes and component bits: what is allocated.
  uint64_t measuredBytes() const;

  // bench --passes' yardstick for this pass: the same geometry drawn with the least lookup of the
  // technique (passes/minimal_lookup.frag) into a target of its own, one map only; `layers` is
  // the channel texture's layer count; esmFallback: with ESM's classification and fallback
  // (WITH_ESM_FALLBACK). Timed by minimalTimer like `timer`: the draw alone.
  void renderMinimalLookup(ProgramCache& programs, const GpuScene& scene,
                           const RenderSettings& settings, const FrameGeometry& frame,
                           const ShadowFilter& shadows, int layers, bool esmFallback);

  Image readMinimalLookupColor() const;  // RGBA in [0,1], linear, row 0 at the top
  // How many times renderMinimalLookup has drawn with and without ESM's fallback: which
  // yardstick a bench row timed leaves no picture once the other has drawn after it.
  int minimalLookupDraws(bool esmFallback) const { return minimalDraws_[esmFallback ? 1 : 0]; }

  GpuTimer timer;
  GpuTimer minimalTimer;

 private:
  int colorTargetCount() const { return lookupInputs_ ? 7 : diagnostics_ ? 3 : 1; }
  void requireDiagnostics() const;
  void requireLookupInputs() const;

  int width_ = 0, height_ = 0;
  bool diagnostics_ = false, lookupInputs_ = false;
  Texture color_, visibility_, diagnostic_, lookup_, receiverPlane_, derivatives_, cascade_, depth_;
  unsigned framebuffer_ = 0;
  // The yardstick's RGBA8 colour and depth, made on its first use.
  Texture minimalColor_, minimalDepth_;
  unsigned minimalFramebuffer_ = 0;
  int minimalWidth_ = 0, minimalHeight_ = 0;
  int minimalDraws_[2] = {0, 0};  // without, with ESM's fallback
};

}  // namespace penumbra::gl
