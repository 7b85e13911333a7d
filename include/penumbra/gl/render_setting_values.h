// The render settings' names and ranges, once: the command line, the settings file and the viewer
// turn names and values into RenderSettings through here, and every front end checks the result
// with validateRenderSettings before any loading or GL work. Renderer::validate adds the limits
// of the GL it runs on.
#pragma once

#include <string>
#include <string_view>

#include "penumbra/gl/renderer.h"
#include "penumbra/shared/filter_weights.h"

namespace penumbra::gl {

// Texels per side of a shadow map and pixels per side of a frame: GL 4.5 guarantees 16384
// (GL_MAX_TEXTURE_SIZE) nowhere, but no GL exceeds it; Renderer::validate checks this GL's own.
inline constexpr int kMinShadowMapSize = 16;
inline constexpr int kMaxTextureSizeAnyGl = 16384;
inline constexpr int kMinFrameSize = 1;
// The blur's odd kernel widths: 1 (none), 3, ..., 2 kMaxBlurRadius + 1.
inline constexpr int kMaxBlurTaps = 2 * shaders::kMaxBlurRadius + 1;
// A Gaussian blur's sigma in texels (PCF's sigma shares the range: params.cpp).
inline constexpr float kMinBlurSigma = 0.01f;
inline constexpr float kMaxBlurSigma = 64.0f;
inline constexpr int kMaxAnisotropy = 16;
inline constexpr float kMaxNormalOffsetTexels = 10.0f;

// Light-pass samples: 1 (off), 2, 4 or 8 (Renderer::validate adds this GL's GL_MAX_SAMPLES);
// throws Error listing them.
void checkMsaaSamples(int samples);

// The blur radius of a kernel `taps` wide; throws Error for an even width or one outside
// [1, kMaxBlurTaps].
int blurRadiusOfTaps(int taps);
// A Gaussian's sigma when none is given: half the radius, so the kernel's ends (r = 2 sigma) sit
// at two standard deviations and keep 5% of the centre's weight, at least 0.5 texels (the blur of
// radius 0 and 1 keeps a sigma its weights can resolve).
float defaultBlurSigma(int radius);
// A sigma given by the user: finite and in [kMinBlurSigma, kMaxBlurSigma]; throws Error.
float checkedBlurSigma(float sigma);

// Names, as the command line and the settings file spell them; parse* throw Error listing the
// valid names.
std::string_view blurKernelName(BlurKernel kernel);  // "gaussian", "box"
BlurKernel parseBlurKernel(std::string_view name);
std::string_view overlayName(Overlay overlay);  // "none", "cascades"
Overlay parseOverlay(std::string_view name);
// CascadeSettings::fitDepthBounds: "fixed" (false) or "fitted" (true).
std::string_view cascadeDepthName(bool fitDepthBounds);
bool parseCascadeDepth(std::string_view name);

// Every setting against its range on any GL, the cascades included (validateCascadeSettings);
// throws Error naming the setting and its range. The technique's parameters are validateParams'.
void validateRenderSettings(const RenderSettings& settings);

}  // namespace penumbra::gl
