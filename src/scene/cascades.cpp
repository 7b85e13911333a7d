// Cascade splits and per-cascade light boxes (tight or stabilised).
#include "penumbra/cascades.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <sstream>
#include <string>

#include "penumbra/error.h"
#include "penumbra/shared/cascade_selection.h"
#include "penumbra/shared/filter_weights.h"

namespace penumbra {
namespace {

std::string str(float v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

// The eight corners of the camera frustum between view depths zn and zf, in world space.
std::array<glm::vec3, 8> sliceCorners(const Camera& camera, float aspect, float zn, float zf) {
  const glm::mat4 worldFromView = glm::inverse(viewFromWorld(camera));
  const float tanHalf = std::tan(glm::radians(camera.verticalFovDegrees) * 0.5f);
  std::array<glm::vec3, 8> corners;
  int k = 0;
  for (float z : {zn, zf}) {
    for (float sy : {-1.0f, 1.0f}) {
      for (float sx : {-1.0f, 1.0f}) {
        const glm::vec4 view(sx * z * tanHalf * aspect, sy * z * tanHalf, -z, 1.0f);
        corners[size_t(k++)] = glm::vec3(worldFromView * view);
      }
    }
  }
  return corners;
}

glm::vec2 lightPlane(const LightView& light, glm::vec3 world) {
  return glm::vec2(light.lightFromWorld * glm::vec4(world, 1.0f));
}

// Tight: the light-plane bounding box of the slice's corners.
glm::vec4 tightBox(const LightView& light, const std::array<glm::vec3, 8>& corners) {
  glm::vec2 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
  for (const glm::vec3& c : corners) {
    const glm::vec2 p = lightPlane(light, c);
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  return {lo, glm::max(hi - lo, glm::vec2(1e-4f))};
}

// Stabilised: the smallest sphere around the slice depends only on the fov, aspect and depths,
// so the box's size stays the same as the camera turns or moves; its centre is snapped to whole
// texels of the light's fixed view plane, so the map moves by whole texels and shadow edges are
// rasterised the same way every frame (Valient, ShaderX6 2008; Dimitrov, NVIDIA 2007).
glm::vec4 stabilizedBox(const LightView& light, const Camera& camera, float aspect, float zn,
                        float zf, int shadowMapSize) {
  const float tanHalf = std::tan(glm::radians(camera.verticalFovDegrees) * 0.5f);
  const float k2 = tanHalf * tanHalf * (1.0f + aspect * aspect);  // (corner radius / depth)^2
  // The centre on the view axis equidistant from the near and far corner rings, at most zf.
  const float zc = std::min(zf, 0.5f * (zf + zn) * (1.0f + k2));
  const float radius = std::sqrt(std::max((zf - zc) * (zf - zc) + zf * zf * k2,
                                          (zc - zn) * (zc - zn) + zn * zn * k2));
  const glm::vec3 forward = glm::normalize(camera.target - camera.position);
  const glm::vec2 centre = lightPlane(light, camera.position + forward * zc);
  // Snapping moves the box's corner down by up to one texel, so the box is one texel wider than
  // the sphere: size texels of 2r / (size - 1) cover [c - r, c + r] wherever the corner lands.
  const float texel = 2.0f * radius / float(shadowMapSize - 1);
  const glm::vec2 corner = glm::floor((centre - radius) / texel) * texel;
  const float size = float(shadowMapSize) * texel;
  return {corner, size, size};
}

}  // namespace

std::string_view cascadeFitName(CascadeFit fit) {
  return fit == CascadeFit::Tight ? "tight" : "stabilized";
}

CascadeFit parseCascadeFit(std::string_view name) {
  for (CascadeFit fit : {CascadeFit::Stabilized, CascadeFit::Tight}) {
    if (name == cascadeFitName(fit)) return fit;
  }
  throw Error("unknown cascade fit '" + std::string(name) + "'; valid fits: stabilized, tight");
}

void validateCascadeSettings(const CascadeSettings& s) {
  if (s.count < 1 || s.count > kMaxCascadeCount) {
    throw Error("cascade count (--cascades) " + std::to_string(s.count) + " is out of range [1, " +
                std::to_string(kMaxCascadeCount) + "]");
  }
  if (!(s.lambda >= 0.0f && s.lambda <= 1.0f)) {
    throw Error("cascade lambda (--cascade-lambda) " + str(s.lambda) + " is out of range [0, 1]");
  }
  if (!(s.blendBand >= 0.0f && s.blendBand <= kMaxCascadeBlendBand)) {
    throw Error("cascade blend band (--cascade-blend) " + str(s.blendBand) + " is out of range [0, " +
                str(kMaxCascadeBlendBand) + "]");
  }
  if (!(s.maxDistance >= 0.0f && s.maxDistance <= kMaxWorldCoordinate)) {
    throw Error("shadow distance (--shadow-distance) " + str(s.maxDistance) +
                " is out of range [0, 1e6] world units (0: the far side of the scene, in whole "
                "diameters)");
  }
  if (!s.distances.empty()) {
    if (int(s.distances.size()) != s.count - 1) {
      throw Error("cascade split distances (--cascade-splits): " + std::to_string(s.count) + " cascades need " +
                  std::to_string(s.count - 1) + " distances, got " +
                  std::to_string(s.distances.size()));
    }
    for (size_t i = 0; i < s.distances.size(); ++i) {
      const float d = s.distances[i];
      if (!(d > 0.0f && d <= kMaxWorldCoordinate) || (i > 0 && !(d > s.distances[i - 1]))) {
        throw Error("cascade split distances (--cascade-splits) must be positive, increasing and at most 1e6 world units; distance " +
                    std::to_string(i + 1) + " is " + str(d));
      }
    }
  }
}

float defaultShadowDistance(const Camera& camera, const Bounds& shadowBounds) {
  const float diameter = std::max(2.0f * shadowBounds.radius(), 1e-3f);
  const float farSide =
      glm::length(camera.position - shadowBounds.centre()) + shadowBounds.radius();
  return diameter * std::max(1.0f, std::ceil(farSide / diameter));
}

void requireCascadableLight(const CascadeSettings& settings, const Light& light) {
  if (settings.count > 1 && light.kind != LightKind::Directional) {
    throw Error("--cascades " + std::to_string(settings.count) +
                " needs a directional light; this scene's light is a " +
                std::string(lightKindName(light.kind)) + " light (use 1 cascade, "
                "or --light-dir for a directional light)");
  }
}

std::vector<float> practicalSplitEnds(float near, float far, int count, float lambda) {
  std::vector<float> ends(static_cast<size_t>(count));
  for (int i = 1; i <= count; ++i) {
    const float t = float(i) / float(count);
    const float logarithmic = near * std::pow(far / near, t);
    const float uniform = near + (far - near) * t;
    ends[size_t(i - 1)] = lambda * logarithmic + (1.0f - lambda) * uniform;
  }
  ends.back() = far;  // exact, not pow's rounding of it
  return ends;
}

glm::mat4 CascadeFrame::clipFromLight(int cascade) const {
  const glm::vec4 b = boxes[size_t(cascade)];
  return glm::ortho(b.x, b.x + b.z, b.y, b.y + b.w, light.nearDistance, light.farDistance);
}

float CascadeFrame::texelWorldSize(int cascade, int shadowMapSize) const {
  const glm::vec4 b = boxes[size_t(cascade)];
  return std::max(b.z, b.w) / float(shadowMapSize);
}

CascadeFrame fitCascades(const CascadeSettings& settings, const Camera& camera, float aspect,
                         DepthRange range, const Light& light, const Bounds& shadowBounds,
                         int shadowMapSize) {
  validateCascadeSettings(settings);
  requireCascadableLight(settings, light);
  CascadeFrame frame;
  frame.light = fitLightView(light, shadowBounds);
  frame.count = settings.count;
  frame.blendBand = settings.blendBand;
  // The shadow distance must not follow the camera, or the splits (and with them the stabilised
  // boxes' sizes) would change every frame: the setting, else the distance to the far side of the
  // scene's bounding sphere rounded up to whole diameters — it covers the scene from wherever the
  // camera is, and stays put while the camera moves within a shell. Fitted depth bounds narrow it
  // to what the camera sees (and give up that stability, as SDSM does).
  float far = settings.maxDistance > 0.0f ? settings.maxDistance
                                          : defaultShadowDistance(camera, shadowBounds);
  float near = range.near;
  if (settings.fitDepthBounds) far = std::min(far, range.far);
  near = std::min(near, far * 0.999f);
  std::vector<float> ends;
  if (settings.distances.empty()) {
    ends = practicalSplitEnds(near, far, settings.count, settings.lambda);
  } else {
    // Given splits must fall strictly inside the range they split: a split outside would leave
    // an empty cascade, and pushing the shadow distance out would override the user's setting.
    for (float d : settings.distances) {
      if (!(d > near && d < far)) {
        std::ostringstream interval;
        interval << "(" << near << ", " << far << ")";
        throw Error("cascade split distance (--cascade-splits) " + str(d) + " is outside the shadow range " +
                    interval.str() + (settings.fitDepthBounds ? " (fitted to the visible depths)" : "") +
                    "; give splits inside it or change --shadow-distance");
      }
    }
    ends = settings.distances;
    ends.push_back(far);
  }
  frame.start = near;
  float start = near;  // where cascade i's own range begins
  float fitFrom = near;  // where its map must begin: the previous cascade's blend band
  for (int i = 0; i < settings.count; ++i) {
    const float end = ends[size_t(i)];
    frame.ends[size_t(i)] = end;
    frame.boxes[size_t(i)] =
        settings.fit == CascadeFit::Stabilized
            ? stabilizedBox(frame.light, camera, aspect, fitFrom, end, shadowMapSize)
            : tightBox(frame.light, sliceCorners(camera, aspect, fitFrom, end));
    // Cascade i fades into i+1 over the last blendBand of its range (cascade_selection.h), so
    // i+1's map reaches back over that band.
    fitFrom = shaders::cascadeBandStart(start, end, settings.blendBand);
    start = end;
  }
  return frame;
}

BlurSpec cascadeBlur(const BlurSpec& nearest, float scale) {
  BlurSpec b = nearest;
  b.radius = shaders::worldConstantKernelRadius(nearest.radius, scale);
  b.sigma = shaders::worldConstantKernelSigma(nearest.sigma, scale);
  return b;
}

}  // namespace penumbra
