// JSON records of renders (nlohmann-json).
#include "penumbra/gl/render_record.h"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "penumbra/channel_layout.h"
#include "penumbra/params.h"

namespace penumbra::gl {
namespace {

// The view depths where this frame's cascades begin and end: [start, end 0, end 1, ...].
std::vector<float> cascadeEnds(const CascadeFrame& frame) {
  std::vector<float> ends{frame.start};
  for (int i = 0; i < frame.count; ++i) ends.push_back(frame.ends[size_t(i)]);
  return ends;
}

}  // namespace

std::string viewJson(const Scene& scene) {
  using nlohmann::ordered_json;
  auto vec = [](glm::vec3 v) { return ordered_json::array({v.x, v.y, v.z}); };
  const Light& l = scene.light;
  ordered_json light = {{"kind", lightKindName(l.kind)}};
  if (l.kind == LightKind::Directional) {
    light["direction"] = vec(l.direction);
  } else {
    light["position"] = vec(l.position);
  }
  if (l.kind == LightKind::Spot) {
    light["target"] = vec(l.target);
    light["spot_angle"] = l.spotAngleDegrees;
  }
  light["size"] = l.size;
  const Camera& c = scene.camera;
  return ordered_json{{"light", light},
                      {"camera",
                       {{"position", vec(c.position)},
                        {"target", vec(c.target)},
                        {"fov", c.verticalFovDegrees}}}}
      .dump();
}

std::string passTimesJson(const PassTimes& t) {
  return nlohmann::ordered_json{{"light", t.light},
                                {"encode", t.encode},
                                {"prefilter", t.prefilter},
                                {"mips_or_sat", t.mipsOrSat},
                                {"auxiliary", t.auxiliary},
                                {"camera", t.camera},
                                {"depth_bounds", t.depthBounds},
                                {"total", t.total()}}
      .dump();
}

std::string passTimesJson(const std::optional<PassTimes>& t) {
  return t ? passTimesJson(*t) : "null";
}

std::string cascadeSettingsJson(const CascadeSettings& c) {
  nlohmann::ordered_json out = {{"count", c.count}};
  if (c.distances.empty()) {
    out["split_scheme"] = "practical";
    out["lambda"] = c.lambda;
  } else {
    out["split_scheme"] = "given";
    out["split_distances"] = c.distances;
  }
  out["fit"] = cascadeFitName(c.fit);
  out["depth_bounds"] = c.fitDepthBounds ? "fitted" : "fixed";
  out["blend_band"] = c.blendBand;
  out["shadow_distance"] = c.maxDistance;  // 0: defaultShadowDistance (cascade_view_depths)
  return out.dump();
}

std::string renderRecordJson(const Scene& scene, const RenderSettings& settings,
                             const RenderResult& result, const std::string& device,
                             const std::map<std::string, std::string>& files) {
  using nlohmann::ordered_json;
  ordered_json params = ordered_json::object();
  for (const ParamSpec& spec : techniqueParamSpecs(settings.technique)) {
    params[std::string(spec.name)] = formatParam(settings.technique, result.params, spec.name);
  }
  const ChannelLayout layout = channelLayout(settings.technique, settings.params);
  double sum = 0.0, lo = 1.0, hi = 0.0;
  for (float v : result.visibility.data()) {
    sum += v;
    lo = std::min(lo, double(v));
    hi = std::max(hi, double(v));
  }
  const MemoryReport& m = result.memory;
  auto times = [](const auto& t) { return ordered_json::parse(passTimesJson(t)); };
  ordered_json record = {
      {"scene", scene.name},
      {"technique", techniqueId(settings.technique)},
      {"technique_title", techniqueTitle(settings.technique)},
      {"params", params},
      // Where the picture was seen and lit from (<stem>_settings.json gives it back to --settings).
      {"view", ordered_json::parse(viewJson(scene))},
      {"light_kind", lightKindName(scene.light.kind)},
      // Light::size: 0 is an ideal point source; else soft shadows (spot: disk diameter in world
      // units, directional: tangent of the angular diameter).
      {"light_size", scene.light.size},
      {"settings",
       {{"shadow_map_size", settings.shadowMapSize},
        {"msaa_samples", settings.msaaSamples},
        {"blur",
         {{"kernel", settings.blur.kernel == BlurKernel::Box ? "box" : "gaussian"},
          {"radius", settings.blur.radius},
          {"taps", 2 * settings.blur.radius + 1},
          {"sigma", settings.blur.sigma}}},
        {"filter", filterModeName(settings.filter)},
        {"anisotropy", settings.anisotropy},
        {"width", settings.width},
        {"height", settings.height},
        {"normal_offset_texels", settings.normalOffsetTexels},
        {"ambient", settings.ambient},
        {"cascades", ordered_json::parse(cascadeSettingsJson(settings.cascades))}}},
      {"channels",
       {{"count", layout.channels},
        {"layers", layout.layers},
        {"components_per_texel", layout.componentsPerTexel},
        {"storage", storageFormatName(layout.format)}}},
      {"gpu_ms", times(result.gpuTimes)},
      {"wall_ms", times(result.wallTimes)},
      {"memory_bytes",
       {{"light_pass", m.lightPass},
        {"technique", m.technique},
        {"summed_area", m.summedArea},
        {"scratch", m.scratch},
        {"auxiliary", m.auxiliary},
        {"frame", m.frame},
        {"total", m.total()},
        {"geometry", m.geometry}}},
      {"technique_memory_mib", double(m.technique + m.summedArea) / (1024.0 * 1024.0)},
      {"visibility",
       {{"mean", sum / double(result.visibility.data().size())}, {"min", lo}, {"max", hi}}},
      {"esm_failure_rate_percent", result.failureRatePercent},
      {"device", device},
      {"files", files},
  };
  if (settings.cascades.count > 1) record["cascade_view_depths"] = cascadeEnds(result.cascadeFrame);
  return record.dump(2) + "\n";
}

}  // namespace penumbra::gl
