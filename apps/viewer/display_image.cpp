// Composing the scene area's pixels.
#include "display_image.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "penumbra/diagnostic_images.h"
#include "penumbra/error.h"
#include "penumbra/image_io.h"
#include "penumbra/metrics.h"
#include "penumbra/srgb.h"

namespace penumbra::viewer {
namespace {

DisplayImage fromLinear(const Image& linear) {
  return {linear.width(), linear.height(), encodeSrgb8(linear)};
}

// A single-channel image as grey, mapped from [lo, hi] to [0, 1], flipped when row 0 is the
// bottom (the renderer's readbacks) so that the display's row 0 is the top.
DisplayImage grey(const Image& image, float lo, float hi, bool flip) {
  DisplayImage out{image.width(), image.height(), {}};
  out.rgb.resize(size_t(out.width) * size_t(out.height) * 3);
  const float scale = hi > lo ? 1.0f / (hi - lo) : 0.0f;
  for (int y = 0; y < out.height; ++y) {
    for (int x = 0; x < out.width; ++x) {
      const float v = image.at(x, flip ? out.height - 1 - y : y);
      const float t = std::isfinite(v) ? std::clamp((v - lo) * scale, 0.0f, 1.0f) : 0.0f;
      const auto byte = uint8_t(std::lround(srgbFromLinear(t) * 255.0f));
      std::fill_n(&out.rgb[(size_t(y) * size_t(out.width) + size_t(x)) * 3], 3, byte);
    }
  }
  return out;
}

}  // namespace

std::string_view viewName(View view) {
  switch (view) {
    case View::Shaded: return "shaded";
    case View::Visibility: return "visibility";
    case View::Error: return "error vs filtered reference";
    case View::TrueError: return "error vs true shadow (ray traced)";
    case View::FailureMask: return "ESM failure mask";
    case View::Layers: return "layers (LVSM, power CDF)";
    case View::ShadowMap: return "shadow map (depth)";
    case View::Channel: return "shadow map channel";
  }
  return "?";
}

std::string_view viewId(View view) {
  switch (view) {
    case View::Shaded: return "shaded";
    case View::Visibility: return "visibility";
    case View::Error: return "error";
    case View::TrueError: return "truth-error";
    case View::FailureMask: return "failures";
    case View::Layers: return "layers";
    case View::ShadowMap: return "shadowmap";
    case View::Channel: return "channel";
  }
  return "?";
}

View parseView(std::string_view id) {
  std::string valid;
  for (View v : kViews) {
    if (viewId(v) == id) return v;
    valid += (valid.empty() ? "" : ", ") + std::string(viewId(v));
  }
  throw Error("unknown view '" + std::string(id) + "'; valid views: " + valid);
}

Image visibilityError(const gl::RenderResult& result, const Image& reference) {
  return signedVisibilityError(result.visibility, reference, litSurfaceMask(result.lookup));
}

Image trueShadowCoverage(const gl::RenderResult& result, const TrueShadowFrame& truth) {
  return penumbra::truth::measuredPixels(litSurfaceMask(result.lookup), truth.trace, truth.match)
      .coverage;
}

VisibilityErrors measureAgainstTrueShadow(const gl::RenderResult& result,
                                          const TrueShadowFrame& truth) {
  return measureVisibilityErrors(result.visibility, truth.trace.visibility,
                                 trueShadowCoverage(result, truth));
}

std::string describeTrueShadowAt(const gl::RenderResult& result, const TrueShadowFrame& truth,
                                 int x, int y) {
  const Image& visibility = truth.trace.visibility;
  if (x < 0 || y < 0 || x >= visibility.width() || y >= visibility.height()) return {};
  if (truth.match.matched.at(x, y) == 0.0f) {
    return "true shadow: not measured (the render and the trace see different surfaces)";
  }
  if (visibility.at(x, y) < 0.0f) return "true shadow: no surface";
  if (truth.trace.reachedByLight.at(x, y) == 0.0f) {
    return "true shadow: not measured (the light does not reach a sub-pixel: terminator, unlit face)";
  }
  char text[128];
  if (litSurfaceMask(result.lookup).at(x, y) == 0.0f) {
    std::snprintf(text, sizeof text, "true shadow %.3f (the shadow test does not decide here)",
                  double(visibility.at(x, y)));
  } else {
    std::snprintf(text, sizeof text, "true shadow %.3f  error %+.3f", double(visibility.at(x, y)),
                  double(result.visibility.at(x, y) - visibility.at(x, y)));
  }
  return text;
}

DisplayImage composeDisplay(View view, const gl::RenderResult& result, const Image* reference,
                            const Image* map, int referenceRows, const TrueShadowFrame* truth) {
  switch (view) {
    case View::Shaded: break;
    case View::Visibility: return grey(result.visibility, 0.0f, 1.0f, false);
    case View::Error: {
      // Until the reference reaches a row: the visibility, dimmed.
      DisplayImage out = grey(result.visibility, 0.0f, 2.0f, false);
      if (reference == nullptr) return out;
      const Image error = visibilityError(result, *reference);
      const int rows = referenceRows < 0 ? out.height : std::min(referenceRows, out.height);
      for (int y = 0; y < rows; ++y) {
        for (int x = 0; x < out.width; ++x) {
          const glm::vec3 c = errorHeatColour(error.at(x, y), kErrorRange);
          uint8_t* p = &out.rgb[(size_t(y) * size_t(out.width) + size_t(x)) * 3];
          for (int i = 0; i < 3; ++i) p[i] = uint8_t(std::lround(c[i] * 255.0f));
        }
      }
      return out;
    }
    case View::TrueError: {
      DisplayImage out = grey(result.visibility, 0.0f, 2.0f, false);
      if (truth == nullptr) return out;
      const Image lit = litSurfaceMask(result.lookup);
      const Image error = signedVisibilityError(result.visibility, truth->trace.visibility,
                                                trueShadowCoverage(result, *truth));
      for (int y = 0; y < out.height; ++y) {
        for (int x = 0; x < out.width; ++x) {
          uint8_t* p = &out.rgb[(size_t(y) * size_t(out.width) + size_t(x)) * 3];
          if (truth->match.matched.at(x, y) == 0.0f) {
            std::copy_n(kSilhouetteColour, 3, p);
          } else if (truth->trace.visibility.at(x, y) < 0.0f) {
            std::copy_n(kNoSurfaceColour, 3, p);
          } else if (lit.at(x, y) > 0.0f && truth->trace.reachedByLight.at(x, y) == 0.0f) {
            std::copy_n(kTerminatorColour, 3, p);
          } else {
            const glm::vec3 c = errorHeatColour(error.at(x, y), kErrorRange);
            for (int i = 0; i < 3; ++i) p[i] = uint8_t(std::lround(c[i] * 255.0f));
          }
        }
      }
      return out;
    }
    case View::FailureMask: return fromLinear(failureMaskImage(result.diagnostic, result.color));
    case View::Layers: return fromLinear(layerIndexImage(result.diagnostic, result.color));
    case View::ShadowMap: return map ? grey(*map, 0.0f, 1.0f, true) : fromLinear(result.color);
    case View::Channel: {
      if (map == nullptr) break;
      // Channels hold moments, exponentials or Fourier coefficients of very different ranges:
      // shown over their own finite range.
      float lo = INFINITY, hi = -INFINITY;
      for (float v : map->data()) {
        if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
      }
      return grey(*map, lo, hi, true);
    }
  }
  return fromLinear(result.color);
}

}  // namespace penumbra::viewer
