// Rendering every technique and the references, and measuring them.
#include "penumbra/compare/comparison.h"
#include "penumbra/compare/shadowed_frame.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <optional>

#include "penumbra/compare/error_regions.h"
#include "penumbra/compare/reference_region.h"
#include "penumbra/compare/truth_measurement.h"
#include "penumbra/error.h"
#include "penumbra/filters.h"
#include "penumbra/params.h"
#include "penumbra/shared/shadow_lookup.h"

namespace penumbra::compare {
namespace {

// A technique whose error is the reference's own rounding: left out of the worst pixel and the
// trouble spots.
bool isTheReference(const ComparisonRequest& request, Technique technique, bool areaLight) {
  return technique == Technique::Pcf && matchedPcfIsReference(request, areaLight);
}

gl::RenderSettings settingsFor(const ComparisonRequest& request, Technique technique,
                               bool areaLight = false) {
  gl::RenderSettings s = request.settings;
  s.technique = technique;
  s.lookupInputs = true;  // the lit-surface masks and the worst pixel's region read them
  if (technique == Technique::Pcf && matchesPcfKernel(request, areaLight)) {
    s.params.pcf = pcfMatchingPrefilter(s);
  }
  return s;
}

// The coverage minus the pixels where the reference darkens a lit truth
// (TruthResult::referenceTooDark): a technique lighter than the reference there is nearer the
// truth, not leaking.
Image whereLeaksCount(const Image& coverage, const std::optional<TruthResult>& truth) {
  if (!truth) return coverage;
  Image mask = coverage;
  for (size_t i = 0; i < mask.data().size(); ++i) {
    if (truth->referenceTooDark.data()[i] > 0.5f) mask.data()[i] = 0.0f;
  }
  return mask;
}

// Errors against a shadow-map reference over `coverage`, its leak columns over `leakCoverage`
// (whereLeaksCount), the leak share still a share of every measured pixel.
VisibilityErrors errorsAgainstReference(const Image& visibility, const Image& reference,
                                        const Image& coverage, const Image& leakCoverage,
                                        double tau) {
  VisibilityErrors e = measureVisibilityErrors(visibility, reference, coverage, tau);
  const VisibilityErrors leaks = measureVisibilityErrors(visibility, reference, leakCoverage, tau);
  e.leakShare = e.pixels > 0 ? leaks.leakShare * double(leaks.pixels) / double(e.pixels) : 0.0;
  e.leakMeanExcess = leaks.leakMeanExcess;
  return e;
}

}  // namespace

gl::RenderResult renderReferenceFor(const ComparisonRequest& request, gl::Renderer& renderer,
                                    const gl::FrameView& view, bool areaLight, int supersample,
                                    unsigned readBack) {
  if (areaLight) {
    return renderer.renderAreaLightReference(request.settings, view, request.areaLightSamples,
                                             supersample);
  }
  gl::RenderSettings settings = request.settings;
  settings.readBack = request.settings.readBack & readBack;  // neither's images beyond its own
  return renderer.renderReference(settings, view, supersample);
}

std::string_view truthKindName(TruthKind kind) {
  return kind == TruthKind::RayTraced ? "raytraced" : "none";
}

TruthKind parseTruthKind(std::string_view name) {
  for (TruthKind k : {TruthKind::RayTraced, TruthKind::None}) {
    if (name == truthKindName(k)) return k;
  }
  throw Error("unknown truth '" + std::string(name) + "': valid truths are raytraced, none");
}

bool matchesPcfKernel(const ComparisonRequest& request, bool areaLight) {
  return request.matchPcfKernel && !areaLight;
}

bool matchedPcfIsReference(const ComparisonRequest& request, bool areaLight) {
  const FilterMode f = request.settings.filter;
  return matchesPcfKernel(request, areaLight) && request.settings.msaaSamples <= 1 &&
         (f == FilterMode::Point || f == FilterMode::Bilinear);
}

shaders::PcfParams pcfMatchingPrefilter(const gl::RenderSettings& settings) {
  // The prefilter's own kernel, the receiver plane and the reference's tie
  // (shared/shadow_lookup.h): the filtered reference itself for point and bilinear lookups, the
  // nearest PCF kernel for mip-mapped ones. PCF's ranges cover the blur's, so nothing is clamped.
  shaders::LookupSettings lookup{};
  lookup.filterMode = int(settings.filter);
  lookup.blurKernel = blurKernelId(settings.blur.kernel);
  lookup.blurRadius = settings.blur.radius;
  lookup.blurSigma = settings.blur.sigma;
  lookup.kernelScale = 1.0f;  // cascade 0's kernel; the lookup scales it per cascade
  return shaders::pcfMatchingPrefilter(lookup);
}

void validateRequest(const ComparisonRequest& request, const gl::Renderer& renderer) {
  checkSceneSource(request.scene);  // throws for an unknown scene or a missing file
  validateOverrides(request.view);
  if (request.techniques.empty()) throw Error("no technique selected for the comparison");
  if (request.supersample < 1 || request.supersample > 8) {
    throw Error("ground-truth supersampling " + std::to_string(request.supersample) +
                " is out of range [1, 8]");
  }
  if (request.pathFrames < 2 || request.pathFrames > 32) {
    throw Error("camera-path frames " + std::to_string(request.pathFrames) +
                " is out of range [2, 32]");
  }
  const int size = request.settings.shadowMapSize;
  if (usesMips(request.settings.filter) && (size & (size - 1)) != 0) {
    throw Error("the filtered reference of " +
                std::string(filterModeName(request.settings.filter)) +
                " lookups needs a power-of-two shadow-map size (mip blocks of 2^L texels); " +
                std::to_string(size) + " is not: use " +
                std::to_string(1 << int(std::floor(std::log2(double(size))))) + " or " +
                std::to_string(2 << int(std::floor(std::log2(double(size))))));
  }
  checkAreaLightSamples(request.areaLightSamples);
  if (request.truth == TruthKind::RayTraced) {
    truth::checkTrueShadowLightSamples(request.truthLightSamples);
  }
  if (!(request.tau > 0.0 && request.tau < 1.0)) {
    throw Error("leak threshold tau " + std::to_string(request.tau) + " is out of range (0, 1)");
  }
  for (Technique t : request.techniques) {
    try {
      renderer.validate(settingsFor(request, t));
    } catch (const Error& e) {
      throw Error("scene '" + request.scene + "' cannot run with technique '" +
                  std::string(techniqueId(t)) + "': " + e.what());
    }
  }
  gl::RenderSettings reference = request.settings;
  reference.width *= request.supersample;
  reference.height *= request.supersample;
  reference.msaaSamples = 1;
  renderer.validate(reference);
}

ComparisonResult runComparison(const ComparisonRequest& request, gl::Renderer& renderer,
                               const Progress& progress) {
  validateRequest(request, renderer);
  ComparisonResult result;
  SceneLoadOptions load = request.sceneLoad;
  load.aspect = float(request.settings.width) / float(request.settings.height);  // the frame's
  result.scene = loadScene(request.scene, load);
  applyOverrides(result.scene, request.view);
  requireCascadableLight(request.settings.cascades, result.scene.light);
  result.areaLight = result.scene.light.size > 0.0f;
  const bool areaLight = result.areaLight;
  for (Technique t : request.techniques) {
    try {
      gl::Renderer::checkSoftShadows(settingsFor(request, t, areaLight), result.scene.light);
    } catch (const Error& e) {
      throw Error("scene '" + request.scene + "' cannot run with technique '" +
                  std::string(techniqueId(t)) + "': " + e.what());
    }
  }
  result.request = request;
  result.device = renderer.deviceDescription();
  const std::vector<Camera> path = result.scene.cameraPath(request.pathFrames);
  const bool measuresShimmer = request.settings.cascades.count > 1;
  const bool traces = request.truth == TruthKind::RayTraced;
  const int total =
      request.pathFrames * (1 + int(request.techniques.size()) * (measuresShimmer ? 3 : 1)) + 1 +
      (traces ? 1 : 0);
  int done = 0;
  auto step = [&](const std::string& what) {
    if (progress) progress(done, total, what);
    ++done;
  };

  std::vector<std::vector<Image>> visibilities(request.techniques.size());
  std::vector<std::vector<Image>> masks(request.techniques.size());
  std::vector<Image> references;
  renderer.setScene(result.scene);  // uploaded once; each frame is a view of it
  // The truth's BVH, built once from the geometry (the same whatever the shadow map).
  std::unique_ptr<truth::RayScene> rays;
  if (traces) rays = std::make_unique<truth::RayScene>(result.scene);
  const bool plays = result.scene.animation.moves();
  // The scene's own animation plays in real time along the path (kClipFramesPerSecond); it is
  // loaded posed at its first frame.
  size_t shownFrame = 0;
  auto showFrame = [&](size_t frame) {
    if (!plays || frame == shownFrame) return;
    poseScene(result.scene, clipTime(result.scene, int(frame)));
    renderer.setScene(result.scene);
    shownFrame = frame;
  };
  // The references of every frame first, then each technique along the whole path: a
  // technique's channels are allocated once for the path, not again at every frame (allocating
  // zero-fills them, a third of a frame on llvmpipe), and its last frame is a warm one.
  std::optional<gl::RenderResult> firstReference;
  std::vector<Image> depths;  // every cascade's depth for the worst pixel's curves
  for (size_t frame = 0; frame < path.size(); ++frame) {
    const gl::FrameView view{path[frame], result.scene.light};
    showFrame(frame);
    step("reference, frame " + std::to_string(frame + 1));
    namespace fi = gl::frame_image;
    // Later frames feed only the flicker's reference visibility.
    gl::RenderResult reference = renderReferenceFor(request, renderer, view, areaLight, 1,
                                                    frame == 0 ? fi::kAll : fi::kVisibility);
    references.push_back(reference.visibility);
    if (frame > 0) continue;
    result.referenceColor = reference.color;
    result.referenceVisibility = reference.visibility;
    result.coverage = litSurfaceMask(reference.lookup);
    if (std::none_of(result.coverage.data().begin(), result.coverage.data().end(),
                     [](float m) { return m > 0.5f; })) {
      // Every metric would be 0 over no pixels: a silent perfect score.
      throw Error("scene '" + result.scene.name + "' shows no lit surface inside the shadow map" +
                  (request.settings.cascades.count > 1 ? "s (is the view beyond --shadow-distance?)"
                                                       : " (does the light face the view?)") +
                  ": nothing to measure");
    }
    // Every cascade's depth (the worst pixel may lie in any), read before the next passes
    // (which may be multisampled) replace them.
    for (int c = 0; c < reference.cascadeFrame.count; ++c)
      depths.push_back(renderer.readDepthMap(c));
    step("supersampled ground truth");
    result.groundTruthVisibility =
        renderReferenceFor(request, renderer, view, areaLight, request.supersample, fi::kVisibility)
            .visibility;
    if (traces) {
      step("ray-traced truth");
      const Image depth = renderer.readCameraDepth();  // the ground truth's sub-pixels
      const int traceStep = done - 1;
      result.truth =
          measureTruth(*rays, request, result.scene, path[frame],
                       {result.coverage, depth, reference.visibility, result.groundTruthVisibility},
                       [&](int rows, int of) {
                         if (progress) {
                           progress(traceStep, total,
                                    "ray-traced truth, row " + std::to_string(rows) + " of " +
                                        std::to_string(of));
                         }
                       });
    }
    firstReference = std::move(reference);
  }
  const gl::RenderResult& reference = *firstReference;
  const Image leakCoverage = whereLeaksCount(result.coverage, result.truth);
  result.techniques.resize(request.techniques.size());
  result.worstRegion.clear();  // kept for the worst pixel's curves, found below
  double worst = -1.0;
  for (size_t k = 0; k < request.techniques.size(); ++k) {
    const Technique t = request.techniques[k];
    TechniqueResult& out = result.techniques[k];
    gl::RenderSettings settings = settingsFor(request, t, areaLight);
    for (size_t frame = 0; frame < path.size(); ++frame) {
      showFrame(frame);
      step(std::string(techniqueId(t)) + ", frame " + std::to_string(frame + 1));
      // The first frame is measured and shown; every frame's visibility and lit surfaces feed
      // the flicker; only the last frame is timed (warm), the others run without waits.
      namespace fi = gl::frame_image;
      // The first frame's diagnostic gives ESM's failure rate.
      settings.readBack =
          fi::kVisibility | fi::kLookup | (frame == 0 ? fi::kColor | fi::kDiagnostic : fi::kNone);
      settings.timing = frame + 1 == path.size();
      const gl::RenderResult r =
          renderer.render(settings, gl::FrameView{path[frame], result.scene.light});
      visibilities[k].push_back(r.visibility);
      masks[k].push_back(litSurfaceMask(r.lookup));
      // Times of the last frame: warm, without the driver's first-use shader compilation.
      out.gpuTimes = r.gpuTimes;
      if (r.wallTimes) out.wallTimes = *r.wallTimes;
      if (frame > 0) continue;
      out.technique = t;
      out.params = r.params;
      out.filtered = errorsAgainstReference(r.visibility, reference.visibility, result.coverage,
                                            leakCoverage, request.tau);
      out.groundTruth = errorsAgainstReference(r.visibility, result.groundTruthVisibility,
                                               result.coverage, leakCoverage, request.tau);
      if (result.truth) {
        out.truth = measureVisibilityErrors(r.visibility, result.truth->visibility,
                                            result.truth->coverage, request.tau);
        out.truthError =
            signedVisibilityError(r.visibility, result.truth->visibility, result.truth->coverage);
        out.filteringRmseOnTruthPixels =
            measureVisibilityErrors(r.visibility, reference.visibility, result.truth->coverage,
                                    request.tau)
                .rmse;
      }
      out.failureRatePercent = r.failureRatePercent;
      out.memory = r.memory;
      out.color = r.color;
      out.visibility = r.visibility;
      out.error = signedVisibilityError(r.visibility, reference.visibility, result.coverage);
      // A NaN error (a visibility that is not a number) is the worst there is.
      if (!isTheReference(request, t, areaLight) && !(out.filtered.maxAbsolute <= worst) &&
          out.filtered.worstX >= 0) {
        worst = out.filtered.maxAbsolute;
        result.worstTechnique = std::string(techniqueId(t));
        result.worstX = out.filtered.worstX;
        result.worstY = out.filtered.worstY;
      }
    }
  }
  // The curves plot the filtered reference's kernel, which an area light does not have.
  if (result.worstX >= 0 && !areaLight) {
    result.worstReceiverDepth = reference.lookup.at(result.worstX, result.worstY, 2);
    // The pixel's own cascade and its kernel (in a blend band the reference also mixes in the
    // next cascade; the curves show the deciding one).
    const int cascade = std::max(0, int(reference.cascades.at(result.worstX, result.worstY, 0)));
    result.worstRegion =
        referenceRegion(depths[size_t(cascade)], reference.lookup, reference.receiverPlane,
                        result.worstX, result.worstY, reference.cascadeBlurs[size_t(cascade)]);
  }
  for (size_t k = 0; k < request.techniques.size(); ++k) {
    result.techniques[k].flicker = temporalFlicker(visibilities[k], references, masks[k]);
  }
  // The result's scene as its first frame showed it (the report describes that frame).
  showFrame(0);
  if (measuresShimmer) {
    // Both fits side by side: the view holds at the path's first camera while the cascades
    // follow the path (FrameView::shadowCamera), so the picture changes only where the maps do.
    // The shadow camera also turns (a quarter degree a frame): tight boxes change size as it
    // turns, which is what the stabilised fit's bounding sphere is for.
    // The scene is held at its first pose (showFrame(0) above): only the maps move.
    std::vector<Camera> shadowPath = path;
    for (size_t frame = 0; frame < shadowPath.size(); ++frame) {
      Camera& c = shadowPath[frame];
      const glm::mat4 turn =
          glm::rotate(glm::mat4(1.0f), glm::radians(kShimmerTurnDegrees * float(frame)),
                      glm::vec3(0.0f, 1.0f, 0.0f));
      c.target = c.position + glm::vec3(turn * glm::vec4(c.target - c.position, 0.0f));
    }
    for (size_t k = 0; k < request.techniques.size(); ++k) {
      const Technique t = request.techniques[k];
      CascadeShimmer shimmer;
      for (CascadeFit fit : {CascadeFit::Stabilized, CascadeFit::Tight}) {
        gl::RenderSettings settings = settingsFor(request, t, areaLight);
        settings.cascades.fit = fit;
        settings.readBack = gl::frame_image::kVisibility | gl::frame_image::kLookup;
        settings.timing = false;
        std::vector<Image> frames, covered;
        for (size_t frame = 0; frame < path.size(); ++frame) {
          step(std::string(techniqueId(t)) + ", shimmer with " + std::string(cascadeFitName(fit)) +
               " cascades, frame " + std::to_string(frame + 1));
          const gl::RenderResult r = renderer.render(
              settings, gl::FrameView{path.front(), result.scene.light, shadowPath[frame]});
          frames.push_back(r.visibility);
          covered.push_back(litSurfaceMask(r.lookup));
        }
        (fit == CascadeFit::Stabilized ? shimmer.stabilized : shimmer.tight) =
            frameToFrameChange(frames, covered);
      }
      result.techniques[k].shimmer = shimmer;
    }
  }
  if (result.scene.troubleSpots.empty()) {
    std::vector<Image> errors;
    for (const TechniqueResult& t : result.techniques) {
      if (!isTheReference(request, t.technique, areaLight)) errors.push_back(t.error);
    }
    result.scene.troubleSpots = largestErrorRegions(errors, 3);
  }
  // Mostly in shadow for the reference and every technique: the view, not the techniques.
  double leastShadowed = shadowedShare(result.referenceVisibility, result.coverage);
  for (const TechniqueResult& t : result.techniques) {
    leastShadowed = std::min(leastShadowed, shadowedShare(t.visibility, result.coverage));
  }
  result.shadowedWarning = mostlyShadowedWarning(result.scene, leastShadowed);
  if (progress) progress(total, total, "measured");
  return result;
}

}  // namespace penumbra::compare
