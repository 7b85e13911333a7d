// The comparison report's files and index.html.
#include "penumbra/compare/report.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include "penumbra/compare/html_text.h"
#include "penumbra/compare/report_plots.h"
#include "penumbra/curves.h"
#include "penumbra/error.h"
#include "penumbra/gl/render_record.h"
#include "penumbra/image_io.h"
#include "penumbra/output_journal.h"
#include "penumbra/params.h"
#include "penumbra/text_file.h"

namespace penumbra::compare {
namespace fs = std::filesystem;
using nlohmann::ordered_json;

namespace {

double mib(uint64_t bytes) {
  return double(bytes) / (1024.0 * 1024.0);
}

uint64_t techniqueBytes(const TechniqueResult& t) {
  return gl::shadowMapBytes(t.memory, t.technique);
}

std::string html(const std::string& text) {
  return escapeHtml(text);
}

std::string slug(const std::string& text) {
  std::string out;
  for (char c : text)
    out += std::isalnum(static_cast<unsigned char>(c)) ? char(std::tolower(c)) : '_';
  return out;
}

// A crop of an image, scaled up by `zoom` with nearest neighbours.
Image crop(const Image& image, glm::vec4 rect, int zoom) {
  const int x0 = std::clamp(int(rect.x * float(image.width())), 0, image.width() - 1);
  const int y0 = std::clamp(int(rect.y * float(image.height())), 0, image.height() - 1);
  const int x1 = std::clamp(int(rect.z * float(image.width())), x0 + 1, image.width());
  const int y1 = std::clamp(int(rect.w * float(image.height())), y0 + 1, image.height());
  Image out((x1 - x0) * zoom, (y1 - y0) * zoom, image.channels());
  for (int y = 0; y < out.height(); ++y) {
    for (int x = 0; x < out.width(); ++x) {
      for (int c = 0; c < image.channels(); ++c)
        out.at(x, y, c) = image.at(x0 + x / zoom, y0 + y / zoom, c);
    }
  }
  return out;
}

// A technique's images with its non-finite pixels (VisibilityErrors::nonFinitePixels) drawn in
// `marker` (every channel of a pixel with any non-finite one): the PNG writers refuse NaN, and the
// page says which pixels these are (nonFiniteNote).
Image markNonFinite(const Image& image, const std::vector<float>& marker) {
  Image out = image;
  const size_t channels = size_t(image.channels());
  for (size_t texel = 0; texel < out.data().size(); texel += channels) {
    bool finite = true;
    for (size_t c = 0; c < channels; ++c) finite = finite && std::isfinite(out.data()[texel + c]);
    if (finite) continue;
    for (size_t c = 0; c < channels; ++c) out.data()[texel + c] = marker[c % marker.size()];
  }
  return out;
}
const std::vector<float> kShadedMarker{1.0f, 0.0f, 1.0f, 1.0f};  // magenta
const std::vector<float> kValueMarker{0.0f};

std::string nonFiniteNote(const TechniqueResult& t) {
  if (t.filtered.nonFinitePixels == 0) return {};
  return "<p><b>" + std::to_string(t.filtered.nonFinitePixels) +
         " covered pixels are not a number</b>: every error column is NaN and the technique ranks "
         "last; they are magenta in the shaded image and 0 in the visibility and error "
         "images.</p>\n";
}

ordered_json errorsJson(const VisibilityErrors& e) {
  return {{"pixels", e.pixels},
          {"non_finite_pixels", e.nonFinitePixels},  // > 0: the errors below are NaN (null)
          {"rmse", e.rmse},
          {"mean_absolute", e.meanAbsolute},
          {"max_absolute", e.maxAbsolute},
          {"psnr_db", e.psnr},
          {"leak_share", e.leakShare},
          {"leak_mean_excess", e.leakMeanExcess},
          {"dark_share", e.darkShare},
          {"dark_mean_excess", e.darkMeanExcess}};
}

ordered_json timesJson(const std::optional<gl::PassTimes>& t) {
  return ordered_json::parse(gl::passTimesJson(t));
}

ordered_json settingsJson(const ComparisonRequest& r) {
  const gl::RenderSettings& s = r.settings;
  return {{"shadow_map_size", s.shadowMapSize},
          {"msaa_samples", s.msaaSamples},
          {"blur",
           {{"kernel", s.blur.kernel == BlurKernel::Box ? "box" : "gaussian"},
            {"taps", 2 * s.blur.radius + 1},
            {"sigma", s.blur.sigma}}},
          {"filter", filterModeName(s.filter)},
          {"anisotropy", s.anisotropy},
          {"width", s.width},
          {"height", s.height},
          {"normal_offset_texels", s.normalOffsetTexels},
          {"ground_truth_supersampling", r.supersample},
          {"camera_path_frames", r.pathFrames},
          {"tau", r.tau},
          {"area_light_samples", r.areaLightSamples},
          {"pcf_kernel_matched_to_prefilter", r.matchPcfKernel},
          {"cascades", ordered_json::parse(gl::cascadeSettingsJson(s.cascades))}};
}

ordered_json paramsJson(Technique t, const TechniqueParams& p) {
  ordered_json out = ordered_json::object();
  for (const ParamSpec& spec : techniqueParamSpecs(t))
    out[std::string(spec.name)] = formatParam(t, p, spec.name);
  return out;
}

ordered_json shimmerJson(const TechniqueResult& t) {
  if (!t.shimmer) return nullptr;
  return {{"stabilized", t.shimmer->stabilized}, {"tight", t.shimmer->tight}};
}

void writeText(const fs::path& path, const std::string& text) {
  writeTextFile(path, text);
}

// What MSAA changes in the measurement: the techniques' light pass is multisampled, the
// references' is not (docs/reference.md).
std::string msaaNote(const ComparisonResult& r) {
  const int samples = r.request.settings.msaaSamples;
  if (samples <= 1) return "off: every light pass is single-sampled";
  return std::to_string(samples) +
         "x MSAA in the techniques' light pass (moments averaged over each texel's samples after "
         "encoding, hard and PCF testing the nearest sample's depth); both references render a "
         "single-sampled light pass, so the sub-texel depths MSAA adds count as error";
}

// A technique's error against the truth in its two parts (docs/reference.md), all three over the
// truth's pixels: the sampling part, the shadow-map reference's own distance to the truth
// (resolution, aliasing, the curved-receiver artefact; the same for every technique), and the
// filtering part, the technique's distance to the reference (its approximation of the step).
ordered_json decompositionJson(const ComparisonResult& r, const TechniqueResult& t) {
  if (!r.truth || !t.truth) return nullptr;
  return {{"total_rmse_vs_truth", t.truth->rmse},
          {"sampling_rmse_reference_vs_truth", r.truth->referenceVsTruth.rmse},
          {"filtering_rmse_vs_reference", t.filteringRmseOnTruthPixels},
          {"pixels", t.truth->pixels}};
}

ordered_json truthJson(const ComparisonResult& r) {
  if (!r.truth) return nullptr;
  const TruthResult& t = *r.truth;
  return {{"kind", "raytraced"},
          {"ray_tracer", truth::embreeDescription()},
          {"light_samples_per_sub_pixel", t.lightSamples},
          {"sub_pixels_per_side", r.request.supersample},
          {"pixels_measured", t.referenceVsTruth.pixels},
          {"excluded_pixels", t.excludedPixels},
          {"mismatched_sub_pixels", t.mismatchedSubPixels},
          {"unlit_pixels", t.unlitPixels},
          {"reference_darker_than_lit_truth_pixels", t.referenceTooDarkPixels},
          {"reference_vs_truth", errorsJson(t.referenceVsTruth)},
          {"ground_truth_vs_truth", errorsJson(t.groundTruthVsTruth)},
          {"triangles", t.triangles},
          {"bvh_seconds", t.bvhSeconds},
          {"trace_seconds", t.traceSeconds},
          {"camera_rays", t.cameraRays},
          {"shadow_rays", t.shadowRays}};
}

std::string vecText(glm::vec3 v) {
  std::ostringstream out;
  out << std::setprecision(4) << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return out.str();
}

// The light and camera in words, so a report's picture can be reproduced.
std::string viewSentence(const Scene& scene) {
  const Light& l = scene.light;
  std::ostringstream out;
  out << std::setprecision(4) << lightKindName(l.kind) << " light ";
  if (l.kind == LightKind::Directional) {
    out << "travelling " << vecText(l.direction);
  } else {
    out << "at " << vecText(l.position);
  }
  if (l.kind == LightKind::Spot) {
    out << " aimed at " << vecText(l.target) << ", cone " << l.spotAngleDegrees << "°";
  }
  if (l.size > 0.0f) out << ", size " << l.size;
  out << "; camera at " << vecText(scene.camera.position) << " looking at "
      << vecText(scene.camera.target) << ", " << scene.camera.verticalFovDegrees
      << "° vertical field of view";
  return out.str();
}

// The error the report ranks by: against the truth when there is one.
double rankingRmse(const TechniqueResult& t) {
  return t.truth ? t.truth->rmse : t.filtered.rmse;
}

void writeMetrics(const ComparisonResult& r, const fs::path& dir) {
  ordered_json techniques = ordered_json::array();
  for (const TechniqueResult& t : r.techniques) {
    techniques.push_back({{"technique", techniqueId(t.technique)},
                          {"title", techniqueTitle(t.technique)},
                          {"params", paramsJson(t.technique, t.params)},
                          {"vs_filtered_reference", errorsJson(t.filtered)},
                          {"vs_ground_truth", errorsJson(t.groundTruth)},
                          {"vs_truth", t.truth ? errorsJson(*t.truth) : ordered_json(nullptr)},
                          {"error_decomposition", decompositionJson(r, t)},
                          {"temporal_flicker", t.flicker},
                          {"shimmer", shimmerJson(t)},
                          {"esm_failure_rate_percent", t.failureRatePercent},
                          {"gpu_ms", timesJson(t.gpuTimes)},
                          {"wall_ms", timesJson(t.wallTimes)},
                          {"technique_memory_bytes", techniqueBytes(t)},
                          {"total_memory_bytes", t.memory.total()}});
  }
  const ordered_json metrics = {
      {"scene", r.scene.name},
      {"scene_description", r.scene.description},
      {"device", r.device},
      {"settings", settingsJson(r.request)},
      {"view", ordered_json::parse(gl::viewJson(r.scene))},
      {"view_warning",
       r.shadowedWarning ? ordered_json(*r.shadowedWarning) : ordered_json(nullptr)},
      {"ranked_by", r.truth ? "rmse against the ray-traced truth (vs_truth)"
                            : "rmse against the filtered reference (vs_filtered_reference)"},
      {"truth", truthJson(r)},
      {"references",
       {{"truth",
         "the true shadow ray traced from the scene's geometry (Embree) at the ground truth's "
         "sub-pixels: the camera ray's first hit, occlusion rays to the light (docs/reference.md)"},
        {"filtered",
         "exact PCF of the raw depth under each technique's effective kernel (blur x lookup), "
         "receiver-plane depth per tap; frame 0 (docs/reference.md)"},
        {"ground_truth", "the filtered reference averaged over supersample^2 sub-pixel positions"},
        {"area_light",
         r.areaLight ? "light size " + std::to_string(r.scene.light.size) +
                           ": both references are the area-light reference (mean of hard tests "
                           "from " +
                           std::to_string(r.request.areaLightSamples) +
                           " stratified points on the light's " +
                           (r.scene.light.kind == LightKind::Point ? "sphere" : "disk") +
                           ") in place of the filtered one"
                     : std::string("none: the light has no size, so the references are the "
                                   "filtered reference and its supersampled ground truth")},
        {"msaa", msaaNote(r)},
        {"columns",
         "vs_truth: against the ray-traced truth over the pixels that see the same surfaces as "
         "the rasterised frame; vs_filtered_reference: rmse, errors, leaks, over-darkening (the "
         "leaks leaving out the pixels where the reference is darker than a lit truth); "
         "vs_ground_truth: the same including minification aliasing; temporal_flicker: along the "
         "camera path against the "
         "filtered reference's own change; shimmer (cascades only): the visibility's mean "
         "frame-to-frame change with the view held at the path's first camera while stabilised "
         "or tight cascades follow the path"}}},
      {"worst_pixel",
       {{"technique", r.worstTechnique},
        {"x", r.worstX},
        {"y", r.worstY},
        {"receiver_depth", r.worstReceiverDepth}}},
      {"techniques", techniques}};
  writeText(dir / "metrics.json", metrics.dump(2) + "\n");

  std::ostringstream csv;
  csv << std::setprecision(8)
      << "technique,rmse,mean_absolute,max_absolute,psnr_db,leak_share,leak_mean_excess,dark_share,"
         "dark_mean_excess,rmse_ground_truth,temporal_flicker,shimmer_stabilized,shimmer_tight,"
         "esm_failure_rate_percent,wall_ms,gpu_ms,technique_memory_bytes,rmse_truth,"
         "leak_share_truth,dark_share_truth,sampling_rmse_reference_vs_truth\n";
  for (const TechniqueResult& t : r.techniques) {
    const VisibilityErrors& e = t.filtered;
    csv << techniqueId(t.technique) << "," << e.rmse << "," << e.meanAbsolute << ","
        << e.maxAbsolute << "," << e.psnr << "," << e.leakShare << "," << e.leakMeanExcess << ","
        << e.darkShare << "," << e.darkMeanExcess << "," << t.groundTruth.rmse << "," << t.flicker
        << ",";
    if (t.shimmer)
      csv << t.shimmer->stabilized << "," << t.shimmer->tight;  // else both empty
    else
      csv << ",";
    csv << "," << t.failureRatePercent << "," << t.wallTimes.total() << ",";
    if (t.gpuTimes) csv << t.gpuTimes->total();  // else empty: not measured
    csv << "," << techniqueBytes(t) << ",";
    if (t.truth && r.truth) {  // else all four empty
      csv << t.truth->rmse << "," << t.truth->leakShare << "," << t.truth->darkShare << ","
          << r.truth->referenceVsTruth.rmse;
    } else {
      csv << ",,,";
    }
    csv << "\n";
  }
  writeText(dir / "metrics.csv", csv.str());
}

// The reference the errors are measured against (docs/reference.md).
std::string referenceName(const ComparisonResult& r) {
  return r.areaLight ? "area-light reference" : "filtered reference";
}

// Soft shadows: what stands in for the filtered reference wherever this page names it.
std::string areaLightNote(const ComparisonResult& r) {
  if (!r.areaLight) return {};
  std::ostringstream h;
  const bool sphere = r.scene.light.kind == LightKind::Point;
  h << "<p><b>Soft shadows, light size " << r.scene.light.size
    << "</b>: the reference is the <b>area-light reference</b>, the mean of the hard shadow tests "
       "of "
    << r.request.areaLightSamples
    << (sphere ? " six-face shadow maps rendered from stratified points of the light's sphere, "
                 "each weighted by the solid angle it covers from the receiver"
               : " shadow maps rendered from stratified points of the light's disk")
    << "; the ground truth is it supersampled. Read \"filtered reference\" below as the "
       "area-light reference (docs/reference.md).</p>\n";
  return h.str();
}

// How PCF ran: matched to the prefilter (the reference itself where the lookup allows) or with
// the user's own parameters.
std::string pcfNote(const ComparisonResult& r) {
  const bool hasPcf =
      std::any_of(r.techniques.begin(), r.techniques.end(),
                  [](const TechniqueResult& t) { return t.technique == Technique::Pcf; });
  if (!hasPcf) return {};
  if (r.areaLight) {
    return "<p><b>PCF is PCSS</b> under the area light: blocker search, penumbra estimate and a "
           "variable kernel (docs/techniques.md), with its own bias.</p>\n";
  }
  if (r.request.matchPcfKernel) {
    std::string note =
        "<p><b>PCF</b> runs with the prefilter's kernel, radius and sigma, no bias and the "
        "receiver-plane test: ";
    if (matchedPcfIsReference(r.request, r.areaLight)) {
      return note +
             "it is the filtered reference itself, so its error is the reference's own "
             "rounding.</p>\n";
    }
    if (r.request.settings.msaaSamples > 1) {
      note += "under " + std::to_string(r.request.settings.msaaSamples) +
              "× MSAA it tests the nearest of each texel's light-pass samples where the reference "
              "tests its single-sampled depth, so it is not the reference: ";
    }
    const FilterMode f = r.request.settings.filter;
    if (f != FilterMode::Point && f != FilterMode::Bilinear) {
      note += std::string("the ") + std::string(filterModeName(f)) +
              " lookup's kernel has no PCF equal, so it runs with the nearest PCF kernel, not "
              "the reference's: ";
    }
    return note + "it is measured like any other technique.</p>\n";
  }
  return "<p><b>PCF is not matched to the prefilter</b>: it runs with its parameters as given "
         "(<code>--param</code> or the settings file), so it is measured like any other "
         "technique, not as the reference.</p>\n";
}

// What the truth is, which pixels it measures, and the references' own distance to it.
std::string truthNote(const ComparisonResult& r) {
  if (!r.truth) {
    return "<p><b>No ray-traced truth</b> (<code>--truth none</code>): the techniques are ranked "
           "against the " +
           referenceName(r) + ".</p>\n";
  }
  const TruthResult& t = *r.truth;
  std::ostringstream h;
  h << std::setprecision(4)
    << "<p><b>Ray-traced truth</b>: the true shadow from the scene's geometry ("
    << html(truth::embreeDescription()) << ", " << t.triangles << " triangles), at the ground "
    << "truth's " << r.request.supersample << "×" << r.request.supersample
    << " sub-pixels: each camera ray's first hit, then "
    << (t.lightSamples > 1 ? std::to_string(t.lightSamples) +
                                 " occlusion rays to stratified points of the light's " +
                                 (r.scene.light.kind == LightKind::Point ? "sphere" : "disk")
                           : std::string("one occlusion ray to the light"))
    << ", started off the surface by its floating-point precision, not a bias ("
    << t.cameraRays + t.shadowRays << " rays in " << t.traceSeconds << " s, BVH " << t.bvhSeconds
    << " s). It is the same whatever the shadow map. The techniques are <b>ranked by their RMSE "
       "against it</b>, over the "
    << t.referenceVsTruth.pixels
    << " lit pixels where the traced and the rasterised frame see the same surface in every "
       "sub-pixel; <b>"
    << t.excludedPixels
    << "</b> covered pixels where they do not (silhouettes) are left out (magenta below), and <b>"
    << t.unlitPixels
    << "</b> where the light does not reach a sub-pixel's surface as the renderer lights it "
       "(cyan below): the shadow terminator of a tessellated surface (the triangle turned away, "
       "its smooth shading normal not: dark in the truth, lit by a shadow map's normal offset), "
       "a pixel straddling a lit and an unlit face, ground outside a spot light's cone.</p>\n"
    << "<p><b>Error decomposition</b>: a technique's error against the truth = the "
       "<i>sampling</i> part, the "
    << referenceName(r) << "'s own distance to the truth (RMSE <b>" << t.referenceVsTruth.rmse
    << "</b>, leak share " << t.referenceVsTruth.leakShare << ", over-darkening share "
    << t.referenceVsTruth.darkShare << "; the supersampled ground truth's RMSE "
    << t.groundTruthVsTruth.rmse
    << "): shadow-map resolution, aliasing, the receiver plane on curved surfaces — plus the "
       "<i>filtering</i> part, the technique's distance to the "
    << referenceName(r) << " (the columns without <i>truth</i>). <b>" << t.referenceTooDarkPixels
    << "</b> pixels that the truth lights but the " << referenceName(r)
    << " darkens by more than τ (orange below: its kernel spreads a shadow past a hard edge, or "
       "its receiver plane misses the curved neighbours of a surface) are left out of the leak "
       "columns against it: a technique lighter than the reference there is nearer the truth, "
       "not leaking.</p>\n";
  return h.str();
}

// Cascaded runs: each technique's shimmer with stabilised and tight fits, side by side.
std::string shimmerSection(const ComparisonResult& r) {
  const bool measured = std::any_of(r.techniques.begin(), r.techniques.end(),
                                    [](const TechniqueResult& t) { return t.shimmer.has_value(); });
  if (!measured) return {};
  const CascadeSettings& c = r.request.settings.cascades;
  std::ostringstream h;
  h << std::setprecision(4) << "<h2>Shimmer</h2>\n<p>" << c.count << " cascades follow the "
    << r.request.pathFrames << "-frame camera path, turning " << kShimmerTurnDegrees
    << "° a frame, while the view holds at its first camera, so the picture changes only where "
       "the shadow maps do. Shimmer: the mean frame-to-frame change of the visibility on lit "
       "surfaces, with the cascades fitted stabilised (bounding sphere, texel snapping) and "
       "tight (bounding box of each split), rendered side by side. Tight boxes follow the "
       "camera, so the maps are resampled every frame and edges crawl; stabilised maps keep "
       "their size and move by whole texels.";
  if (c.fitDepthBounds) {
    h << " Here the depth bounds are fitted to what the shadow camera sees, so the splits move "
         "every frame and the stabilised maps change size too (the sample-distribution "
         "trade-off).";
  }
  h << "</p>\n"
    << "<table id=\"shimmer\"><thead><tr><th>technique</th><th>stabilised</th><th>tight</th>"
       "<th>tight / stabilised</th></tr></thead><tbody>\n";
  for (const TechniqueResult& t : r.techniques) {
    if (!t.shimmer) continue;
    h << "<tr><td>" << techniqueId(t.technique) << "</td><td>" << t.shimmer->stabilized
      << "</td><td>" << t.shimmer->tight << "</td><td>";
    if (t.shimmer->stabilized > 0.0)
      h << t.shimmer->tight / t.shimmer->stabilized;
    else
      h << "—";
    h << "</td></tr>\n";
  }
  h << "</tbody></table>\n";
  return h.str();
}

void writeHtml(const ComparisonResult& r, const fs::path& dir, bool hasCurves) {
  const auto& spots = r.scene.troubleSpots;
  // The GPU column only where some technique's frame has GPU times (never on llvmpipe).
  const bool gpuTimed = std::ranges::any_of(
      r.techniques, [](const TechniqueResult& t) { return t.gpuTimes.has_value(); });
  std::ostringstream h;
  h << std::setprecision(4);
  h << R"(<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<title>penumbra comparison: )"
    << html(r.scene.name) << R"(</title>
<style>
body{font-family:sans-serif;margin:24px;max-width:1400px;color:#222}
table{border-collapse:collapse;font-size:13px}th,td{border:1px solid #ccc;padding:4px 8px;text-align:right}
th{background:#eee;cursor:pointer;user-select:none}td:first-child,th:first-child{text-align:left}
img{max-width:100%;border:1px solid #ddd}.row{display:flex;flex-wrap:wrap;gap:12px;align-items:flex-start}
.row figure{margin:0}figcaption{font-size:12px;color:#555}code{background:#f4f4f4;padding:1px 4px}
</style></head><body>
<h1>penumbra comparison — )"
    << html(r.scene.name) << "</h1>\n<p>" << html(r.scene.description)
    << "</p>\n<p>Device: " << html(r.device) << ". Shadow map " << r.request.settings.shadowMapSize
    << "², " << (2 * r.request.settings.blur.radius + 1) << "-tap "
    << (r.request.settings.blur.kernel == BlurKernel::Box ? "box" : "Gaussian") << " prefilter, "
    << filterModeName(r.request.settings.filter) << " lookups, " << r.request.settings.width << "×"
    << r.request.settings.height << ", ground truth " << r.request.supersample << "×"
    << r.request.supersample << " sub-pixels, flicker over " << r.request.pathFrames
    << " camera-path frames";
  if (r.scene.animation.moves()) {
    h << " as its animation '" << html(r.scene.animation.clip) << "' plays ("
      << kClipFramesPerSecond << " frames a second from its start)";
  }
  h << ", τ = " << r.request.tau;
  const CascadeSettings& cascades = r.request.settings.cascades;
  if (cascades.count > 1) {
    h << ", " << cascades.count << " " << cascadeFitName(cascades.fit) << " cascades ("
      << (cascades.distances.empty() ? "practical splits" : "given splits") << ", "
      << (cascades.fitDepthBounds ? "fitted" : "fixed") << " depth bounds, blend band "
      << cascades.blendBand << "; the reference is evaluated in each pixel's cascade)";
  }
  if (r.request.settings.msaaSamples > 1) {
    h << ", " << r.request.settings.msaaSamples << "× MSAA in the techniques' light pass";
  }
  h << ".</p>\n"
    << "<p><b>View</b>: " << html(viewSentence(r.scene)) << " (<code>metrics.json</code> "
    << "<code>view</code>).</p>\n"
    << (r.shadowedWarning ? "<p style=\"background:#fee;border:1px solid #c33;padding:8px\"><b>"
                            "This frame ranks the view, not the techniques</b>: " +
                                html(*r.shadowedWarning) + "</p>\n"
                          : std::string())
    << truthNote(r) << areaLightNote(r)
    << (r.request.settings.msaaSamples > 1 ? "<p><b>MSAA</b>: " + html(msaaNote(r)) + ".</p>\n"
                                           : std::string())
    << "<p><b>Filtered reference</b>: exact PCF of the raw depth map under each technique's "
       "effective kernel "
       "(blur × lookup), each tap tested against the receiver plane. <b>Ground truth</b>: the "
       "filtered "
       "reference averaged over sub-pixels, so minification aliasing counts as error. Error "
       "columns are "
       "against the filtered reference unless marked <i>GT</i>; see "
       "<code>metrics.json</code>.</p>\n"
    << pcfNote(r)
    << "<h2>All techniques</h2>\n<img src=\"grid.png\" alt=\"grid of all techniques\">\n"
    << "<h2>Metrics</h2>\n<p>Ranked by RMSE against the "
    << (r.truth ? std::string("ray-traced truth") : referenceName(r))
    << "; click a column to sort.</p>\n<table id=\"metrics\"><thead><tr>"
    << "<th>technique</th><th>rank</th>"
    << (r.truth ? "<th>RMSE truth</th><th>leak share truth</th><th>dark share truth</th>" : "")
    << "<th>RMSE</th><th>mean abs</th><th>max abs</th><th>PSNR "
       "dB</th><th>leak "
       "share</th>"
       "<th>leak excess</th><th>dark share</th><th>dark excess</th><th>RMSE GT</th><th>flicker</th>"
       "<th>ESM fail %</th><th>wall ms</th>"
    << (gpuTimed ? "<th>GPU ms</th>" : "") << "<th>memory MiB</th></tr></thead><tbody>\n";
  const std::vector<const TechniqueResult*> ranked = rankTechniques(r);
  for (size_t rank = 0; rank < ranked.size(); ++rank) {
    const TechniqueResult& t = *ranked[rank];
    const VisibilityErrors& e = t.filtered;
    h << "<tr><td><a href=\"#" << techniqueId(t.technique) << "\">" << techniqueId(t.technique)
      << "</a></td><td>" << rank + 1 << "</td><td>";
    if (t.truth) {
      h << t.truth->rmse << "</td><td>" << t.truth->leakShare << "</td><td>" << t.truth->darkShare
        << "</td><td>";
    }
    h << e.rmse << "</td><td>" << e.meanAbsolute << "</td><td>" << e.maxAbsolute << "</td><td>"
      << e.psnr << "</td><td>" << e.leakShare << "</td><td>" << e.leakMeanExcess << "</td><td>"
      << e.darkShare << "</td><td>" << e.darkMeanExcess << "</td><td>" << t.groundTruth.rmse
      << "</td><td>" << t.flicker << "</td><td>" << t.failureRatePercent << "</td><td>"
      << t.wallTimes.total() << "</td><td>";
    if (gpuTimed) {
      if (t.gpuTimes) {
        h << t.gpuTimes->total();
      } else {
        h << "—";
      }
      h << "</td><td>";
    }
    h << mib(techniqueBytes(t)) << "</td></tr>\n";
  }
  h << "</tbody></table>\n"
    << "<p><b>Times</b>: the camera path's last frame (warm: no first-use shader compilation); "
       "<i>wall ms</i> between glFinish calls around each pass"
    << (gpuTimed ? ", <i>GPU ms</i> by timer queries.</p>\n"
                 : std::string("; no GPU ms: ") + gl::kNoGpuTimesReason + ".</p>\n")
    << shimmerSection(r) << "<h2>Error against cost</h2>\n<div class=\"row\">"
    << "<img src=\"plots/error_vs_memory.png\" alt=\"error against memory\">"
    << "<img src=\"plots/error_vs_time.png\" alt=\"error against time\"></div>\n";
  if (hasCurves) {
    h << "<h2>The worst pixel</h2>\n<p>Pixel (" << r.worstX << ", " << r.worstY
      << "), worst for <b>" << html(r.worstTechnique)
      << "</b>; its reference kernel's depths (moved along the receiver plane), "
      << "receiver at depth " << r.worstReceiverDepth
      << ", every technique's shadow test over receiver depth "
      << "(<code>penumbra curves</code>; data in <code>plots/worst_pixel_curves.csv</code>):</p>\n"
      << "<img src=\"plots/worst_pixel_curves.png\" alt=\"curves of the worst pixel\">\n";
  }
  h << "<h2>References</h2>\n<div class=\"row\"><figure><img src=\"images/reference_shaded.png\" "
       "alt=\"reference\">"
    << "<figcaption>" << referenceName(r)
    << ", shaded</figcaption></figure><figure><img src=\"images/reference_visibility.png\" "
    << "alt=\"reference visibility\"><figcaption>" << referenceName(r)
    << " visibility</figcaption></figure><figure>"
    << "<img src=\"images/ground_truth_visibility.png\" alt=\"ground truth "
       "visibility\"><figcaption>supersampled "
    << "ground truth visibility</figcaption></figure></div>\n";
  if (r.truth) {
    h << "<div class=\"row\"><figure><img src=\"images/truth_shaded.png\" alt=\"truth\">"
         "<figcaption>ray-traced truth, shaded</figcaption></figure><figure>"
         "<img src=\"images/truth_visibility.png\" alt=\"truth visibility\"><figcaption>"
         "ray-traced truth visibility</figcaption></figure><figure>"
         "<img src=\"images/truth_pixels.png\" alt=\"pixels measured against the truth\">"
         "<figcaption>magenta: left out (another surface in a sub-pixel); cyan: left out (the "
         "light does not reach a sub-pixel); orange: the "
      << referenceName(r) << " darker than the lit truth</figcaption></figure></div>\n";
  }
  for (const TechniqueResult& t : r.techniques) {
    const std::string id(techniqueId(t.technique));
    h << "<h2 id=\"" << id << "\">" << id << " — " << html(std::string(techniqueTitle(t.technique)))
      << "</h2>\n"
      << "<p>";
    if (t.truth) {
      h << "Against the truth: RMSE " << t.truth->rmse << ", leak share " << t.truth->leakShare
        << ", over-darkening share " << t.truth->darkShare << ". Against the " << referenceName(r)
        << ": ";
    }
    h << "RMSE " << t.filtered.rmse << ", leak share " << t.filtered.leakShare
      << ", over-darkening share " << t.filtered.darkShare << ", flicker " << t.flicker
      << "; parameters: <code>" << html(paramsJson(t.technique, t.params).dump()) << "</code></p>\n"
      << nonFiniteNote(t) << "<div class=\"row\">"
      << "<figure><img src=\"images/" << id << "_shaded.png\" alt=\"" << id
      << " shaded\"><figcaption>shaded</figcaption></figure>"
      << "<figure><img src=\"images/" << id << "_visibility.png\" alt=\"" << id
      << " visibility\"><figcaption>visibility</figcaption></figure>"
      << "<figure><img src=\"images/" << id << "_error.png\" alt=\"" << id
      << " error\"><figcaption>error against the " << referenceName(r) << "</figcaption></figure>";
    if (t.truth) {
      h << "<figure><img src=\"images/" << id << "_truth_error.png\" alt=\"" << id
        << " error against the truth\"><figcaption>error against the ray-traced "
           "truth</figcaption></figure>";
    }
    h << "</div>\n";
    if (!spots.empty()) {
      h << "<div class=\"row\">";
      for (const TroubleSpot& spot : spots) {
        h << "<figure><img src=\"crops/" << id << "_" << slug(spot.name) << ".png\" alt=\""
          << html(spot.name) << "\"><figcaption>" << html(spot.name) << " (" << id
          << ")</figcaption></figure>"
          << "<figure><img src=\"crops/reference_" << slug(spot.name) << ".png\" alt=\"reference "
          << html(spot.name) << "\"><figcaption>" << html(spot.name)
          << " (reference)</figcaption></figure>";
      }
      h << "</div>\n";
    }
  }
  h << R"(<script>
// Sortable metrics table.
document.querySelectorAll('#metrics th').forEach(function (th, column) {
  th.addEventListener('click', function () {
    var body = document.querySelector('#metrics tbody');
    var rows = Array.prototype.slice.call(body.rows);
    var ascending = th.dataset.order !== 'ascending';
    th.dataset.order = ascending ? 'ascending' : 'descending';
    rows.sort(function (a, b) {
      var x = a.cells[column].textContent, y = b.cells[column].textContent;
      var nx = parseFloat(x), ny = parseFloat(y);
      var order = isNaN(nx) || isNaN(ny) ? x.localeCompare(y) : nx - ny;
      return ascending ? order : -order;
    });
    rows.forEach(function (row) { body.appendChild(row); });
  });
});
// Self-check for tests: every image must have loaded.
window.addEventListener('load', function () {
  var images = Array.prototype.slice.call(document.images);
  var broken = images.filter(function (img) { return !img.complete || img.naturalWidth === 0; });
  document.body.dataset.imagesLoaded = String(images.length - broken.length);
  document.body.dataset.imagesBroken = String(broken.length);
});
</script>
</body></html>
)";
  writeText(dir / "index.html", h.str());
}

// The truth's visibility with the pixels no camera ray hit (-1) shown as 1, as the rasterised
// references show the sky (nothing drawn: nothing shadowed).
Image untracedAsLit(const Image& visibility) {
  Image out = visibility;
  for (float& v : out.data()) v = v < 0.0f ? 1.0f : v;
  return out;
}

std::string rankingName(const ComparisonResult& r) {
  return "RMSE against the " + (r.truth ? std::string("ray-traced truth") : referenceName(r));
}

// The truth's shaded image in grey (so that no model's own colour reads as a mark) with the
// pixels it does not measure marked: magenta where a sub-pixel sees another surface than the
// rasterised frame, cyan where the light reaches none, orange where the reference darkens a lit
// truth.
Image truthPixelsImage(const ComparisonResult& r) {
  Image image = r.truth->color;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      const float grey = 0.2126f * image.at(x, y, 0) + 0.7152f * image.at(x, y, 1) +
                         0.0722f * image.at(x, y, 2);  // Rec. 709 luminance of linear RGB
      for (int c = 0; c < 3; ++c) image.at(x, y, c) = grey;
      glm::vec3 mark(-1.0f);
      const float excluded = r.truth->exclusion.at(x, y);
      if (excluded == truth::kExcludedSurface) mark = {1.0f, 0.0f, 1.0f};  // magenta
      if (excluded == truth::kExcludedUnlit) mark = {0.0f, 0.8f, 0.9f};    // cyan
      if (r.truth->referenceTooDark.at(x, y) > 0.5f) mark = {1.0f, 0.45f, 0.0f};
      if (mark.x < 0.0f) continue;
      for (int c = 0; c < 3; ++c) image.at(x, y, c) = mark[c];
    }
  }
  return image;
}

void writeContents(const ComparisonResult& r, const fs::path& dir) {
  // Not create_directories: a staging folder removed under us (an interrupt) must stay removed.
  for (const char* sub : {"images", "crops", "plots"}) {
    std::error_code ec;
    recordOutput(dir / sub);
    fs::create_directory(dir / sub, ec);
    if (ec) throw Error("cannot create " + (dir / sub).string() + ": " + ec.message());
  }
  const double range = 0.5;
  GnuplotRun gnuplot(dir);  // every figure of the report, drawn in one batch
  std::vector<GridTile> tiles;
  writeColorPng(r.referenceColor, dir / "images" / "reference_shaded.png");
  // Visibility is a quantity, not light: its value is the grey level (no sRGB encoding).
  writeGrey16Png(r.referenceVisibility, dir / "images" / "reference_visibility.png");
  writeGrey16Png(r.groundTruthVisibility, dir / "images" / "ground_truth_visibility.png");
  if (r.truth) {
    writeColorPng(r.truth->color, dir / "images" / "truth_shaded.png");
    writeGrey16Png(untracedAsLit(r.truth->visibility), dir / "images" / "truth_visibility.png");
    writeColorPng(truthPixelsImage(r), dir / "images" / "truth_pixels.png");
  }
  tiles.push_back({dir / "images" / "reference_shaded.png", referenceName(r)});
  for (const TroubleSpot& spot : r.scene.troubleSpots) {
    writeColorPng(crop(r.referenceColor, spot.rect, 3),
                  dir / "crops" / ("reference_" + slug(spot.name) + ".png"));
  }
  std::vector<ScatterPoint> byMemory, byTime;
  for (const TechniqueResult& t : r.techniques) {
    const std::string id(techniqueId(t.technique));
    const Image color = markNonFinite(t.color, kShadedMarker);
    writeColorPng(color, dir / "images" / (id + "_shaded.png"));
    writeGrey16Png(markNonFinite(t.visibility, kValueMarker),
                   dir / "images" / (id + "_visibility.png"));
    plotErrorHeatMap(gnuplot, markNonFinite(t.error, kValueMarker), range,
                     id + ": visibility error against the " + referenceName(r),
                     dir / "images" / (id + "_error.png"));
    if (t.truth) {
      plotErrorHeatMap(gnuplot, markNonFinite(t.truthError, kValueMarker), range,
                       id + ": visibility error against the ray-traced truth",
                       dir / "images" / (id + "_truth_error.png"));
    }
    for (const TroubleSpot& spot : r.scene.troubleSpots) {
      writeColorPng(crop(color, spot.rect, 3),
                    dir / "crops" / (id + "_" + slug(spot.name) + ".png"));
    }
    tiles.push_back({dir / "images" / (id + "_shaded.png"), id});
    byMemory.push_back({id, std::max(mib(techniqueBytes(t)), 1e-3), rankingRmse(t)});
    byTime.push_back({id, std::max(t.wallTimes.total(), 1e-3), rankingRmse(t)});
  }
  // gnuplot scales each image into its tile keeping its aspect (size ratio -1). A tile is at most
  // twice as tall as wide whatever the frame's shape: cairo refuses surfaces beyond 32767 pixels,
  // which a frame's height / width ratio would otherwise reach (1 x 270 gave 113400 per tile).
  const int tileWidth = 420;
  const int tileHeight =
      std::clamp(tileWidth * r.referenceColor.height() / std::max(1, r.referenceColor.width()), 1,
                 2 * tileWidth);
  plotImageGrid(gnuplot, tiles, 3, tileWidth, tileHeight, dir / "grid.png");
  plotParetoScatter(gnuplot, byMemory, "technique memory (MiB, log scale)", rankingName(r),
                    r.scene.name + ": error against memory", true,
                    dir / "plots" / "error_vs_memory.png");
  plotParetoScatter(gnuplot, byTime, "frame time (wall ms, log scale)", rankingName(r),
                    r.scene.name + ": error against time", true,
                    dir / "plots" / "error_vs_time.png");
  const bool hasCurves = !r.worstRegion.empty();
  if (hasCurves) {
    CurvesRequest curves;
    curves.occluders = r.worstRegion;
    for (const TechniqueResult& t : r.techniques) curves.techniques.push_back(t.technique);
    curves.params = r.techniques.front().params;
    for (const TechniqueResult& t : r.techniques) {
      // Each technique's own parameters as used (they live in separate blocks of the struct).
      if (t.technique == Technique::Lvsm) curves.params.lvsm = t.params.lvsm;
      if (t.technique == Technique::Pcf) curves.params.pcf = t.params.pcf;
    }
    curves.samples = 501;
    const CurvesTable table = computeCurves(curves);
    writeCurvesCsv(table, dir / "plots" / "worst_pixel_curves.csv");
    std::ostringstream title;
    title << "worst pixel (" << r.worstX << ", " << r.worstY << ") of " << r.worstTechnique
          << ", receiver at " << std::setprecision(4) << r.worstReceiverDepth;
    plotCurves(gnuplot, dir / "plots" / "worst_pixel_curves.csv", table, title.str(),
               dir / "plots" / "worst_pixel_curves.png");
  }
  gnuplot.run();
  writeMetrics(r, dir);
  writeHtml(r, dir, hasCurves);
}

}  // namespace

std::vector<const TechniqueResult*> rankTechniques(const ComparisonResult& result) {
  std::vector<const TechniqueResult*> ranked;
  for (const TechniqueResult& t : result.techniques) ranked.push_back(&t);
  // NaN compares false with everything, which is no strict weak order: sort on (NaN, rmse).
  std::stable_sort(ranked.begin(), ranked.end(),
                   [](const TechniqueResult* a, const TechniqueResult* b) {
                     const double ea = rankingRmse(*a), eb = rankingRmse(*b);
                     const bool aNaN = std::isnan(ea), bNaN = std::isnan(eb);
                     if (aNaN != bNaN) return bNaN;
                     return !aNaN && ea < eb;
                   });
  return ranked;
}

void writeReportFiles(const ComparisonResult& result, const fs::path& dir) {
  writeContents(result, dir);
}

}  // namespace penumbra::compare
