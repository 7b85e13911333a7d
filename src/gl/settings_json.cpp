// Settings files as JSON keyed by the command line's option names.
#include "penumbra/gl/settings_json.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "penumbra/error.h"
#include "penumbra/gl/render_setting_values.h"
#include "penumbra/params.h"

namespace penumbra::gl {
namespace {

using nlohmann::json;

constexpr std::string_view kKeys[] = {
    "scene",          "technique",   "param",         "shadow-size",   "msaa",
    "blur",           "blur-kernel", "blur-sigma",    "filter",        "aniso",
    "width",          "height",      "normal-offset", "cascades",      "cascade-lambda",
    "cascade-splits", "cascade-fit", "cascade-depth", "cascade-blend", "shadow-distance",
    "overlay",        "light",       "camera",        "ground",        "casters"};
// The viewer's split view: a key of the file, no option of the command line (settingsKeys()).
constexpr std::string_view kSplitKey = "split";

std::string keyList() {
  std::string list;
  for (std::string_view k : kKeys) list += (list.empty() ? "" : ", ") + std::string(k);
  return list + ", " + std::string(kSplitKey);
}

// Where a value sits, for messages: `file: "key"`.
struct At {
  const std::string& source;
  std::string key;
  std::string str() const { return source + ": \"" + key + "\""; }
  [[noreturn]] void fail(const std::string& what) const { throw Error(str() + " " + what); }
};

double number(const json& v, const At& at, double min, double max) {
  if (!v.is_number()) at.fail("must be a number");
  const double d = v.get<double>();
  if (!std::isfinite(d) || d < min || d > max) {
    std::ostringstream range;
    range << "is " << v.dump() << "; the range is [" << min << ", " << max << "]";
    at.fail(range.str());
  }
  return d;
}

// Values whose range validateOverrides or validateRenderSettings checks after reading.
constexpr struct {
  double min = -std::numeric_limits<float>::max();
  double max = std::numeric_limits<float>::max();
} kAnyFinite;

int integer(const json& v, const At& at, int min, int max) {
  if (!v.is_number_integer()) at.fail("must be a whole number");
  return int(number(v, at, min, max));
}

std::string text(const json& v, const At& at) {
  if (!v.is_string()) at.fail("must be a string");
  return v.get<std::string>();
}

// Rethrows a library Error (unknown name, bad value) with the file and key in front.
template <typename F>
auto withLocation(const At& at, F&& f) {
  try {
    return f();
  } catch (const Error& e) {
    throw Error(at.str() + ": " + e.what());
  }
}

glm::vec3 vector3(const json& v, const At& at) {
  if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() ||
      !v[2].is_number()) {
    at.fail("must be an array of three numbers");
  }
  return {v[0].get<float>(), v[1].get<float>(), v[2].get<float>()};
}

// The float as the shortest decimal that reads back to it, so files say 0.1 and not
// 0.10000000149011612.
json shortest(float f) {
  char buffer[32];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, f);
  return std::stod(std::string(buffer, end));
}

json vectorJson(const glm::vec3& v) {
  return json::array({shortest(v.x), shortest(v.y), shortest(v.z)});
}

void applyView(const std::string& key, const json& value, const std::string& source,
               SceneOverrides& o) {
  const At where{source, key};
  if (!value.is_object()) where.fail("must be an object");
  for (const auto& [field, v] : value.items()) {
    const At at{source, key + "." + field};
    if (key == "light" && field == "kind") {
      try {
        o.lightKind = parseLightKind(text(v, at));
      } catch (const Error& e) {
        at.fail(std::string("is not a light kind: ") + e.what());
      }
    } else if (key == "light" && field == "direction") {
      o.lightDirection = vector3(v, at);
    } else if (key == "light" && field == "position") {
      o.lightPosition = vector3(v, at);
    } else if (key == "light" && field == "target") {
      o.lightTarget = vector3(v, at);
    } else if (key == "light" && field == "spot_angle") {
      o.spotAngleDegrees = float(number(v, at, kAnyFinite.min, kAnyFinite.max));  // checked below
    } else if (key == "light" && field == "size") {
      // validateOverrides (below) and, against the light's kind, applyOverrides check it.
      o.lightSize = float(number(v, at, kAnyFinite.min, kAnyFinite.max));
    } else if (key == "camera" && field == "position") {
      o.cameraPosition = vector3(v, at);
    } else if (key == "camera" && field == "target") {
      o.cameraTarget = vector3(v, at);
    } else if (key == "camera" && field == "fov") {
      o.cameraFovDegrees = float(number(v, at, kAnyFinite.min, kAnyFinite.max));  // checked below
    } else {
      at.fail(std::string("is not a setting; ") + key + " takes " +
              (key == "light" ? "kind, direction, position, target, spot_angle, size"
                              : "position, target, fov"));
    }
  }
  if (key == "light" && o.lightDirection && o.lightPosition) {
    where.fail("gives both a direction (directional light) and a position (spot light); give one");
  }
  withLocation(where, [&] { validateOverrides(o); });
}

// `key`: where the object sits, for messages ("param", "split.param").
void applyParams(const json& value, const std::string& source, TechniqueParams& params,
                 const std::string& key = "param") {
  const At where{source, key};
  if (!value.is_object()) {
    where.fail("must be an object of techniques: {\"vsm\": {\"min_variance\": 1e-5}}");
  }
  for (const auto& [id, values] : value.items()) {
    const At at{source, key + "." + id};
    const Technique technique = withLocation(at, [&] { return parseTechnique(id); });
    if (!values.is_object()) at.fail("must be an object of parameter values");
    // JSON objects have no order to rely on, and some parameters set others (setParam): the
    // layer count first (it places the splits uniformly), then the split list (it sets the layer
    // count, and LVSM's fixed placement, which a "placement" in the same file may set back), then
    // the rest, so that every value the file gives is the value used.
    const auto rank = [technique](const std::string& name) {
      if (name == kLayerCountParam) return 0;
      for (const ParamSpec& spec : techniqueParamSpecs(technique)) {
        if (spec.name == name && spec.kind == ParamKind::SplitList) return 1;
      }
      return 2;
    };
    const auto valueText = [](const json& v) {
      return v.is_string() ? v.get<std::string>() : v.dump();
    };
    const std::string layersKey(kLayerCountParam);
    for (int pass = 0; pass <= 2; ++pass) {
      for (const auto& [name, v] : values.items()) {
        if (rank(name) != pass) continue;
        const At param{source, key + "." + id + "." + name};
        if (!v.is_number() && !v.is_string()) param.fail("must be a number or a string");
        withLocation(param, [&] { setParam(technique, params, name, valueText(v)); });
        if (pass != 1 || !values.contains(layersKey)) continue;
        const std::string layers = formatParam(technique, params, kLayerCountParam);
        if (valueText(values[layersKey]) != layers) {
          param.fail("places " + layers + " layers, but \"" + layersKey + "\" is " +
                     values[layersKey].dump() + ": give one of them, or make them agree");
        }
      }
    }
  }
}

// The viewer's split view: its own technique and parameters (checked by the same registry), and
// where the divider sits.
SplitSettings splitSide(const json& value, const std::string& source) {
  const At where{source, "split"};
  if (!value.is_object())
    where.fail("must be an object: {\"technique\": \"pcf\", \"param\": {...}}");
  SplitSettings split;
  for (const auto& [field, v] : value.items()) {
    const At at{source, "split." + field};
    if (field == "technique") {
      split.technique = withLocation(at, [&] { return parseTechnique(text(v, at)); });
    } else if (field == "param") {
      applyParams(v, source, split.params, "split.param");
    } else if (field == "divider") {
      split.divider = float(number(v, at, 0.0, 1.0));
    } else {
      at.fail("is not a setting; split takes technique, param, divider");
    }
  }
  withLocation(where, [&] { validateParams(split.technique, split.params); });
  return split;
}

std::vector<Technique> techniqueList(const json& v, const At& at) {
  std::vector<Technique> techniques;
  std::string_view list;
  const std::string listText = text(v, at);
  list = listText;
  while (true) {
    const size_t comma = list.find(',');
    techniques.push_back(withLocation(at, [&] { return parseTechnique(list.substr(0, comma)); }));
    if (comma == std::string_view::npos) break;
    list.remove_prefix(comma + 1);
  }
  return techniques;
}

void applyKey(const std::string& key, const json& v, const std::string& source, Settings& s) {
  const At at{source, key};
  RenderSettings& r = s.render;
  if (key == "scene") {
    s.scene = text(v, at);
  } else if (key == "technique") {
    s.techniques = techniqueList(v, at);
  } else if (key == "param") {
    applyParams(v, source, r.params);
  } else if (key == kSplitKey) {
    s.split = splitSide(v, source);
  } else if (key == "shadow-size") {
    r.shadowMapSize = integer(v, at, kMinShadowMapSize, kMaxTextureSizeAnyGl);
  } else if (key == "msaa") {
    r.msaaSamples = integer(v, at, 1, 8);
    withLocation(at, [&] { checkMsaaSamples(r.msaaSamples); });
  } else if (key == "blur") {
    const int taps = integer(v, at, 1, kMaxBlurTaps);
    r.blur.radius = withLocation(at, [&] { return blurRadiusOfTaps(taps); });
    r.blur.sigma = defaultBlurSigma(r.blur.radius);  // "blur-sigma" may follow
  } else if (key == "blur-kernel") {
    const std::string name = text(v, at);
    r.blur.kernel = withLocation(at, [&] { return parseBlurKernel(name); });
  } else if (key == "blur-sigma") {
    r.blur.sigma = float(number(v, at, kMinBlurSigma, kMaxBlurSigma));
  } else if (key == "filter") {
    const std::string name = text(v, at);
    r.filter = withLocation(at, [&] { return parseFilterMode(name); });
  } else if (key == "aniso") {
    r.anisotropy = integer(v, at, 1, kMaxAnisotropy);
  } else if (key == "width") {
    r.width = integer(v, at, kMinFrameSize, kMaxTextureSizeAnyGl);
  } else if (key == "height") {
    r.height = integer(v, at, kMinFrameSize, kMaxTextureSizeAnyGl);
  } else if (key == "normal-offset") {
    r.normalOffsetTexels = float(number(v, at, 0.0, kMaxNormalOffsetTexels));
  } else if (key == "cascades") {
    r.cascades.count = integer(v, at, 1, kMaxCascadeCount);
  } else if (key == "cascade-lambda") {
    r.cascades.lambda = float(number(v, at, 0.0, 1.0));
  } else if (key == "cascade-splits") {
    if (!v.is_array()) at.fail("must be an array of increasing view depths");
    r.cascades.distances.clear();
    for (const json& d : v) {
      r.cascades.distances.push_back(float(number(d, at, 0.0, kMaxWorldCoordinate)));
    }
  } else if (key == "cascade-fit") {
    const std::string name = text(v, at);
    r.cascades.fit = withLocation(at, [&] { return parseCascadeFit(name); });
  } else if (key == "cascade-depth") {
    const std::string name = text(v, at);
    r.cascades.fitDepthBounds = withLocation(at, [&] { return parseCascadeDepth(name); });
  } else if (key == "cascade-blend") {
    r.cascades.blendBand = float(number(v, at, 0.0, kMaxCascadeBlendBand));
  } else if (key == "shadow-distance") {
    r.cascades.maxDistance = float(number(v, at, 0.0, kMaxWorldCoordinate));
  } else if (key == "overlay") {
    const std::string name = text(v, at);
    r.overlay = withLocation(at, [&] { return parseOverlay(name); });
  } else if (key == "ground") {
    const std::string name = text(v, at);
    s.ground = withLocation(at, [&] { return parseGroundMode(name); });
  } else if (key == "casters") {
    const std::string name = text(v, at);
    s.casters = withLocation(at, [&] { return parseCasterMode(name); });
  } else if (key == "light" || key == "camera") {
    // A light kind in the file replaces the light kind set before (as on the command line).
    if (key == "light") {
      s.view.lightKind.reset();
      s.view.lightDirection.reset();
      s.view.lightPosition.reset();
      s.view.lightTarget.reset();
      s.view.spotAngleDegrees.reset();
    }
    applyView(key, v, source, s.view);
  } else {
    at.fail("is not a setting; valid keys: " + keyList());
  }
}

json parseObject(std::string_view text, const std::string& source) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    // nlohmann's parse errors carry the line and column.
    throw Error(source + " is not valid JSON: " + e.what());
  }
  if (!j.is_object()) throw Error(source + " must hold a JSON object");
  return j;
}

std::string readText(const std::filesystem::path& path, const char* what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(std::string("cannot open ") + what + " " + path.string());
  std::ostringstream content;
  content << in.rdbuf();
  return content.str();
}

// A technique's every parameter, numbers as numbers.
json paramsJson(Technique t, const TechniqueParams& params) {
  json values = json::object();
  for (const ParamSpec& spec : techniqueParamSpecs(t)) {
    const std::string value = formatParam(t, params, spec.name);
    const bool numeric =
        (spec.kind == ParamKind::Real || spec.kind == ParamKind::Integer) && value != "auto";
    values[std::string(spec.name)] = !numeric                          ? json(value)
                                     : spec.kind == ParamKind::Integer ? json(std::stoll(value))
                                                                       : json(std::stod(value));
  }
  return values;
}

}  // namespace

std::span<const std::string_view> settingsKeys() {
  return kKeys;
}

void applySettingsJson(std::string_view text, const std::string& source, Settings& settings,
                       std::span<const std::string> skip) {
  const json j = parseObject(text, source);
  // "blur" sets the sigma that goes with its width, so an explicit "blur-sigma" is applied after.
  const auto applyIfPresent = [&](const std::string& key) {
    if (!j.contains(key) || std::find(skip.begin(), skip.end(), key) != skip.end()) return;
    applyKey(key, j.at(key), source, settings);
  };
  applyIfPresent("blur");
  for (const auto& [key, value] : j.items()) {
    if (key == "blur") continue;
    if (std::find(skip.begin(), skip.end(), key) != skip.end()) {
      // Still checked, so a typo in a value the command line overrides does not go unnoticed.
      if (std::find(std::begin(kKeys), std::end(kKeys), key) == std::end(kKeys) &&
          key != kSplitKey) {
        At{source, key}.fail("is not a setting; valid keys: " + keyList());
      }
      continue;
    }
    applyKey(key, value, source, settings);
  }
  withLocation(At{source, "render settings"}, [&] { validateRenderSettings(settings.render); });
  for (Technique t : settings.techniques) {
    withLocation(At{source, "param"}, [&] { validateParams(t, settings.render.params); });
  }
}

void applySettingsFile(const std::filesystem::path& path, Settings& settings,
                       std::span<const std::string> skip) {
  applySettingsJson(readText(path, "settings file"), path.string(), settings, skip);
}

std::string settingsJson(const Settings& s) {
  const RenderSettings& r = s.render;
  json j;
  j["scene"] = s.scene;
  std::string techniques;
  for (Technique t : s.techniques) {
    techniques += (techniques.empty() ? "" : ",") + std::string(techniqueId(t));
  }
  j["technique"] = techniques;
  json params = json::object();
  for (Technique t : s.techniques) params[std::string(techniqueId(t))] = paramsJson(t, r.params);
  j["param"] = params;
  j["shadow-size"] = r.shadowMapSize;
  j["msaa"] = r.msaaSamples;
  j["blur"] = 2 * r.blur.radius + 1;
  j["blur-kernel"] = std::string(blurKernelName(r.blur.kernel));
  j["blur-sigma"] = shortest(r.blur.sigma);
  j["filter"] = std::string(filterModeName(r.filter));
  j["aniso"] = r.anisotropy;
  j["width"] = r.width;
  j["height"] = r.height;
  j["normal-offset"] = shortest(r.normalOffsetTexels);
  j["cascades"] = r.cascades.count;
  j["cascade-lambda"] = shortest(r.cascades.lambda);
  json splits = json::array();
  for (float d : r.cascades.distances) splits.push_back(shortest(d));
  j["cascade-splits"] = splits;
  j["cascade-fit"] = std::string(cascadeFitName(r.cascades.fit));
  j["cascade-depth"] = std::string(cascadeDepthName(r.cascades.fitDepthBounds));
  j["cascade-blend"] = shortest(r.cascades.blendBand);
  j["shadow-distance"] = shortest(r.cascades.maxDistance);
  j["overlay"] = std::string(overlayName(r.overlay));
  j["ground"] = std::string(groundModeName(s.ground));
  j["casters"] = std::string(casterModeName(s.casters));
  const SceneOverrides& v = s.view;
  json light = json::object(), camera = json::object();
  if (v.lightKind) light["kind"] = std::string(lightKindName(*v.lightKind));
  if (v.lightDirection) light["direction"] = vectorJson(*v.lightDirection);
  if (v.lightPosition) light["position"] = vectorJson(*v.lightPosition);
  if (v.lightTarget) light["target"] = vectorJson(*v.lightTarget);
  if (v.spotAngleDegrees) light["spot_angle"] = shortest(*v.spotAngleDegrees);
  if (v.lightSize) light["size"] = shortest(*v.lightSize);
  if (v.cameraPosition) camera["position"] = vectorJson(*v.cameraPosition);
  if (v.cameraTarget) camera["target"] = vectorJson(*v.cameraTarget);
  if (v.cameraFovDegrees) camera["fov"] = shortest(*v.cameraFovDegrees);
  if (!light.empty()) j["light"] = light;
  if (!camera.empty()) j["camera"] = camera;
  if (s.split) {
    json split;
    split["technique"] = std::string(techniqueId(s.split->technique));
    split["param"] = json::object({{std::string(techniqueId(s.split->technique)),
                                    paramsJson(s.split->technique, s.split->params)}});
    split["divider"] = shortest(s.split->divider);
    j[std::string(kSplitKey)] = split;
  }
  return j.dump(2) + "\n";
}

void writeSettingsFile(const std::filesystem::path& path, const Settings& settings) {
  const std::string text = settingsJson(settings);
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw Error("cannot write settings file " + path.string());
}

void applyViewFile(const std::filesystem::path& path, SceneOverrides& overrides) {
  const std::string source = path.string();
  const json j = parseObject(readText(path, "view file"), source);
  for (const auto& [key, value] : j.items()) {
    if (key != "light" && key != "camera") {
      At{source, key}.fail("is not a setting; the file takes \"light\" and \"camera\"");
    }
    applyView(key, value, source, overrides);
  }
}

}  // namespace penumbra::gl
