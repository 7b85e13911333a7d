// The JSON record of a render: every parameter, per-pass GPU times, exact memory, the device.
#pragma once

#include <map>
#include <optional>
#include <string>

#include "penumbra/gl/renderer.h"

namespace penumbra::gl {

// Pretty-printed JSON. `files` maps roles ("color", "visibility_exr", ...) to written file names.
std::string renderRecordJson(const Scene& scene, const RenderSettings& settings,
                             const RenderResult& result, const std::string& device,
                             const std::map<std::string, std::string>& files);

// The view a picture was made from, as a compact JSON object: {"light": {"kind", "direction"
// or "position" (and a spot's "target" and "spot_angle"), "size"}, "camera": {"position",
// "target", "fov"}} — the render record's and compare's metrics' "view".
std::string viewJson(const Scene& scene);

// Milliseconds per pass as a compact JSON object, for the render record and compare's metrics;
// null for times that were not measured (RenderResult::gpuTimes on a software rasteriser, and
// both on a frame that was not timed).
std::string passTimesJson(const PassTimes& times);
std::string passTimesJson(const std::optional<PassTimes>& times);

// The cascade settings as a compact JSON object (count, split scheme or distances, fit, depth
// bounds, blend band, shadow distance), for the render record and compare's metrics.
std::string cascadeSettingsJson(const CascadeSettings& cascades);

}  // namespace penumbra::gl
