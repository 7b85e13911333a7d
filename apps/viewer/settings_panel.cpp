// The settings panel.
#include "settings_panel.h"

#include <imgui.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <deque>
#include <string>
#include <utility>

#include "penumbra/error.h"
#include "penumbra/filter_mode.h"
#include "penumbra/gl/render_setting_values.h"
#include "penumbra/params.h"
#include "penumbra/shared/filter_weights.h"

namespace penumbra::viewer {
namespace {

std::string shortest(double value) {
  char buffer[32];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, end);
}

// Hover help: the registry's description, range or choices, and default.
void paramHelp(Technique technique, const ParamSpec& spec) {
  if (!ImGui::IsItemHovered()) return;
  std::string range;
  if (spec.kind == ParamKind::Real || spec.kind == ParamKind::Integer) {
    range = "[" + shortest(spec.min) + ", " + shortest(spec.max) + "]";
  } else if (spec.kind == ParamKind::Choice) {
    for (const ParamChoice& c : spec.choices)
      range += (range.empty() ? "" : ", ") + std::string(c.name);
  } else {
    range = "comma-separated split depths";
  }
  const TechniqueParams defaults = defaultTechniqueParams();
  ImGui::SetTooltip("%s\nrange: %s\ndefault: %s", std::string(spec.description).c_str(),
                    range.c_str(), formatParam(technique, defaults, spec.name).c_str());
}

// Sets a parameter from text through the registry, which checks it; a refusal becomes the
// panel's message.
bool trySetParam(ViewerState& state, TechniqueParams& params, Technique technique,
                 const ParamSpec& spec, const std::string& value) {
  try {
    setParam(technique, params, spec.name, value);
    return true;
  } catch (const Error& e) {
    state.message = e.what();
    state.messageIsError = true;
    return false;
  }
}

// `side` tells apart the widgets of the split view's two parameter sets.
bool paramWidget(ViewerState& state, TechniqueParams& params, Technique technique,
                 const ParamSpec& spec, const char* side) {
  const std::string label =
      std::string(spec.name) + "##" + std::string(techniqueId(technique)) + side;
  const std::string current = formatParam(technique, params, spec.name);
  bool changed = false;
  switch (spec.kind) {
    case ParamKind::Real: {
      if (spec.acceptsAuto) {
        bool isAuto = current == "auto";
        if (ImGui::Checkbox(("auto##" + label).c_str(), &isAuto)) {
          changed |=
              trySetParam(state, params, technique, spec, isAuto ? "auto" : shortest(spec.min));
        }
        paramHelp(technique, spec);
        if (isAuto) break;
        ImGui::SameLine();
      }
      float value = current == "auto" ? float(spec.min) : std::stof(current);
      // Ranges over many decades (variances, exponents' bounds) need a logarithmic slider.
      const bool logarithmic = spec.min > 0.0 && spec.max / spec.min > 100.0;
      if (ImGui::SliderFloat(label.c_str(), &value, float(spec.min), float(spec.max), "%.6g",
                             logarithmic ? ImGuiSliderFlags_Logarithmic : 0)) {
        changed |= trySetParam(state, params, technique, spec, shortest(double(value)));
      }
      break;
    }
    case ParamKind::Integer: {
      int value = std::stoi(current);
      if (ImGui::SliderInt(label.c_str(), &value, int(spec.min), int(spec.max))) {
        changed |= trySetParam(state, params, technique, spec, std::to_string(value));
      }
      break;
    }
    case ParamKind::Choice: {
      if (ImGui::BeginCombo(label.c_str(), current.c_str())) {
        for (const ParamChoice& c : spec.choices) {
          if (ImGui::Selectable(std::string(c.name).c_str(), c.name == current)) {
            changed |= trySetParam(state, params, technique, spec, std::string(c.name));
          }
        }
        ImGui::EndCombo();
      }
      break;
    }
    case ParamKind::SplitList: {
      char buffer[256];
      std::snprintf(buffer, sizeof buffer, "%s", current.c_str());
      if (ImGui::InputText(label.c_str(), buffer, sizeof buffer,
                           ImGuiInputTextFlags_EnterReturnsTrue)) {
        changed |= trySetParam(state, params, technique, spec, buffer);
      }
      break;
    }
  }
  paramHelp(technique, spec);
  return changed;
}

template <typename T>
bool comboOf(const char* label, T& value, std::span<const T> options, std::string (*name)(T)) {
  bool changed = false;
  if (ImGui::BeginCombo(label, name(value).c_str())) {
    for (const T& option : options) {
      if (ImGui::Selectable(name(option).c_str(), option == value)) {
        changed = option != value;
        value = option;
      }
    }
    ImGui::EndCombo();
  }
  return changed;
}

std::string techniqueLabel(Technique t) {
  return std::string(techniqueId(t)) + "  (" + std::string(techniqueTitle(t)) + ")";
}
std::string filterLabel(FilterMode f) {
  return std::string(filterModeName(f));
}
std::string intLabel(int i) {
  return std::to_string(i);
}
std::string viewLabel(View v) {
  return std::string(viewName(v));
}

constexpr FilterMode kFilters[] = {
    FilterMode::Point,       FilterMode::Bilinear,          FilterMode::Trilinear,
    FilterMode::Anisotropic, FilterMode::AnisotropicDriver, FilterMode::SummedArea};
constexpr int kShadowSizes[] = {64, 128, 256, 512, 1024, 2048, 4096};
constexpr int kMsaa[] = {1, 2, 4, 8};

void sceneSection(ViewerState& state, Changes& changes) {
  if (ImGui::BeginCombo("scene", state.settings.scene.c_str())) {
    for (std::string_view name : builtinSceneNames()) {
      if (ImGui::Selectable(std::string(name).c_str(), name == state.settings.scene)) {
        state.settings.scene = std::string(name);
        state.settings.view = {};  // the new scene's own camera and light
        changes.scene = true;
      }
    }
    ImGui::EndCombo();
  }
  static char path[512] = "";
  ImGui::InputText("file", path, sizeof path);
  ImGui::SameLine();
  if (ImGui::Button("open") && path[0] != '\0') {
    state.settings.scene = path;
    state.settings.view = {};
    changes.scene = true;
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("a .gltf, .glb or .obj file, as --scene takes");
  const SceneAnimation& animation = state.scene.animation;
  if (animation.moves()) {
    ImGui::Checkbox(("play '" + animation.clip + "'").c_str(), &state.playing);
    if (ImGui::SliderFloat("time (s)", &state.clipSeconds, 0.0f, animation.duration, "%.2f")) {
      state.playing = false;  // a time picked by hand holds
      changes.pose = true;
    }
  }
}

void techniqueSection(ViewerState& state, Changes& changes) {
  Technique& shown = state.settings.techniques.front();
  if (comboOf("technique", shown, allTechniques(), techniqueLabel)) changes.render = true;
  for (const ParamSpec& spec : techniqueParamSpecs(shown)) {
    changes.render |= paramWidget(state, state.settings.render.params, shown, spec, "left");
  }
  if (ImGui::Button("defaults")) {
    state.settings.render.params = defaultTechniqueParams();
    changes.render = true;
  }
}

// The split view: a second technique, or the same one with a second parameter set, right of a
// draggable divider.
void splitSection(ViewerState& state, Changes& changes) {
  if (ImGui::Checkbox("split view", &state.split)) {
    if (state.split) state.splitParams = state.settings.render.params;
    changes.render = true;
  }
  if (!state.split) return;
  if (comboOf("right technique", state.splitTechnique, allTechniques(), techniqueLabel)) {
    changes.render = true;
  }
  for (const ParamSpec& spec : techniqueParamSpecs(state.splitTechnique)) {
    changes.render |= paramWidget(state, state.splitParams, state.splitTechnique, spec, "right");
  }
  if (ImGui::Button("copy left parameters")) {
    state.splitParams = state.settings.render.params;
    changes.render = true;
  }
  ImGui::TextDisabled("drag the divider in the scene; left: the technique above");
}

void renderSection(ViewerState& state, Changes& changes) {
  gl::RenderSettings& r = state.settings.render;
  changes.render |=
      comboOf("shadow map", r.shadowMapSize, std::span<const int>(kShadowSizes), intLabel);
  changes.render |= comboOf("MSAA", r.msaaSamples, std::span<const int>(kMsaa), intLabel);
  changes.render |= comboOf("filter", r.filter, std::span<const FilterMode>(kFilters), filterLabel);
  if (r.filter == FilterMode::Anisotropic || r.filter == FilterMode::AnisotropicDriver) {
    changes.render |= ImGui::SliderInt("anisotropy", &r.anisotropy, 1, gl::kMaxAnisotropy);
  }
  int taps = 2 * r.blur.radius + 1;
  if (ImGui::SliderInt("blur taps", &taps, 1, gl::kMaxBlurTaps)) {
    r.blur.radius = std::max(0, (taps - 1) / 2);
    r.blur.sigma = gl::defaultBlurSigma(r.blur.radius);
    changes.render = true;
  }
  bool box = r.blur.kernel == BlurKernel::Box;
  if (ImGui::Checkbox("box kernel", &box)) {
    r.blur.kernel = box ? BlurKernel::Box : BlurKernel::Gaussian;
    changes.render = true;
  }
  if (!box)
    changes.render |= ImGui::SliderFloat("blur sigma", &r.blur.sigma, gl::kMinBlurSigma,
                                         gl::kMaxBlurSigma, "%.2f", ImGuiSliderFlags_Logarithmic);
  changes.render |= ImGui::SliderFloat("normal offset", &r.normalOffsetTexels, 0.0f,
                                       gl::kMaxNormalOffsetTexels, "%.2f texels");
  changes.render |= ImGui::SliderInt("frame width", &r.width, 16, 1920);
  changes.render |= ImGui::SliderInt("frame height", &r.height, 16, 1080);
  if (state.light.kind == LightKind::Directional) {
    changes.render |= ImGui::SliderInt("cascades", &r.cascades.count, 1, kMaxCascadeCount);
    if (r.cascades.count > 1) {
      changes.render |= ImGui::SliderFloat("split lambda", &r.cascades.lambda, 0.0f, 1.0f);
      changes.render |= ImGui::SliderFloat("blend band", &r.cascades.blendBand, 0.0f, 0.5f);
      bool tight = r.cascades.fit == CascadeFit::Tight;
      if (ImGui::Checkbox("tight fit (shimmers)", &tight)) {
        r.cascades.fit = tight ? CascadeFit::Tight : CascadeFit::Stabilized;
        changes.render = true;
      }
      changes.render |= ImGui::Checkbox("fit depth bounds", &r.cascades.fitDepthBounds);
      bool tint = r.overlay == gl::Overlay::Cascades;
      if (ImGui::Checkbox("cascade colours", &tint)) {
        r.overlay = tint ? gl::Overlay::Cascades : gl::Overlay::None;
        changes.render = true;
      }
    }
  }
}

void lightSection(ViewerState& state, Changes& changes) {
  Light& light = state.light;
  int kind = int(light.kind);
  bool kindChanged = false;
  for (const LightKind k : {LightKind::Directional, LightKind::Spot, LightKind::Point}) {
    if (k != LightKind::Directional) ImGui::SameLine();
    kindChanged |= ImGui::RadioButton(std::string(lightKindName(k)).c_str(), &kind, int(k));
  }
  if (kindChanged) {
    // The command line's --light: where a light of the new kind stands comes from the library
    // (applyOverrides), so the viewer and `render --light` place it alike.
    Scene placed = state.scene;
    placed.light = light;
    placed.light.size = 0.0f;  // each kind has its own range and meaning of the size
    SceneOverrides kindOnly;
    kindOnly.lightKind = LightKind(kind);
    try {
      applyOverrides(placed, kindOnly);
      light = placed.light;
      if (light.kind != LightKind::Directional) state.settings.render.cascades.count = 1;
      changes.render = true;
    } catch (const Error& e) {  // e.g. a spot light aimed from the scene's centre at it
      state.message = e.what();
      state.messageIsError = true;
    }
  }
  if (light.kind == LightKind::Directional) {
    float azimuth = 0.0f, elevation = 0.0f;
    lightAnglesOf(light.direction, azimuth, elevation);
    bool moved = ImGui::SliderFloat("light azimuth", &azimuth, -180.0f, 180.0f, "%.1f deg");
    moved |= ImGui::SliderFloat("light elevation", &elevation, 1.0f, 90.0f, "%.1f deg");
    if (moved) light.direction = lightDirectionFrom(azimuth, elevation);
    changes.render |= moved;
  } else {
    changes.render |= ImGui::DragFloat3("light position", &light.position.x, 0.05f);
  }
  if (light.kind == LightKind::Spot) {
    changes.render |= ImGui::DragFloat3("light target", &light.target.x, 0.05f);
    changes.render |=
        ImGui::SliderFloat("spot angle", &light.spotAngleDegrees, 1.0f, 170.0f, "%.1f deg");
  }
  // Light::size: a spot light's disk diameter and a point light's sphere diameter in world units,
  // a directional light's tangent of its angular diameter (docs/techniques.md); 0: hard shadows.
  {
    const bool spot = light.kind == LightKind::Spot;
    const bool point = light.kind == LightKind::Point;
    const float most = spot    ? kMaxSpotLightSize
                       : point ? kMaxPointLightSize
                               : kMaxDirectionalLightSize;
    if (light.size > most) {  // the other kind's range: a directional light takes at most 0.5
      light.size = most;
      changes.render = true;
    }
    const char* format = spot    ? "%.3f (disk diameter)"
                         : point ? "%.3f (sphere diameter)"
                                 : "%.4f (tan of diameter)";
    changes.render |= ImGui::SliderFloat("light size", &light.size, 0.0f, most, format);
    if (ImGui::IsItemHovered()) {
      ImGui::SetTooltip(
          "soft shadows: PCSS for pcf, contact-hardening filters for the filterable "
          "techniques (trilinear, anisotropic or sat filtering); 0: hard-edged light");
    }
  }
  ImGui::TextDisabled("shift + drag in the scene moves the light");
}

void cameraSection(ViewerState& state, Changes& changes) {
  int mode = state.cameraMode == CameraMode::Fly ? 1 : 0;
  if (ImGui::RadioButton("orbit", &mode, 0) |
      (ImGui::SameLine(), ImGui::RadioButton("fly", &mode, 1))) {
    state.cameraMode = mode == 1 ? CameraMode::Fly : CameraMode::Orbit;
  }
  changes.render |= ImGui::SliderFloat("field of view", &state.camera.verticalFovDegrees, 5.0f,
                                       120.0f, "%.1f deg");
  if (ImGui::Button("reset view")) changes.scene = true;
  ImGui::TextDisabled(state.cameraMode == CameraMode::Orbit
                          ? "drag: orbit, right drag / wheel: dolly, middle drag: pan"
                          : "drag: look, W A S D Q E: move");
}

void viewSection(ViewerState& state, const FrameStats& stats, Changes& changes) {
  changes.display |= comboOf("show", state.view, std::span<const View>(kViews), viewLabel);
  if (state.view == View::Channel && stats.result != nullptr) {
    const int channels = channelCount(state.settings.techniques.front(), stats.result->params);
    state.channel = std::min(state.channel, channels - 1);
    changes.display |= ImGui::SliderInt("channel", &state.channel, 0, channels - 1);
  }
  if ((state.view == View::ShadowMap || state.view == View::Channel) && stats.result != nullptr) {
    const int cascades = stats.result->cascadeFrame.count;
    state.mapCascade = std::clamp(state.mapCascade, 0, cascades - 1);
    if (cascades > 1) {
      changes.display |= ImGui::SliderInt("cascade", &state.mapCascade, 0, cascades - 1);
    }
  }
  if (state.view == View::Error) {
    ImGui::TextDisabled("red: leaks light, blue: over-darkens (+-%.1f saturates)",
                        double(kErrorRange));
    ImGui::TextWrapped("%s", state.referenceStatus.c_str());
  }
  if (state.view == View::TrueError) {
    ImGui::TextDisabled("red: leaks light, blue: over-darkens (+-%.1f saturates)",
                        double(kErrorRange));
    const auto swatch = [](const uint8_t(&c)[3]) {
      return ImVec4(float(c[0]) / 255.0f, float(c[1]) / 255.0f, float(c[2]) / 255.0f, 1.0f);
    };
    ImGui::TextColored(swatch(kSilhouetteColour), "green: silhouettes, not measured");
    ImGui::TextColored(swatch(kTerminatorColour), "amber: unlit (terminator), not measured");
    ImGui::SameLine();
    ImGui::TextDisabled("grey: no surface");
    ImGui::TextWrapped("%s", state.truthStatus.c_str());
  }
}

// The last frames' time of each pass as a rolling graph, one colour per pass, stacked so that the
// top is the frame's total.
void drawPassGraph(const std::deque<gl::PassTimes>& history) {
  if (history.empty()) return;
  using Pass = double gl::PassTimes::*;
  static constexpr std::pair<const char*, Pass> kPasses[] = {
      {"light", &gl::PassTimes::light},         {"encode", &gl::PassTimes::encode},
      {"blur", &gl::PassTimes::prefilter},      {"mips/SAT", &gl::PassTimes::mipsOrSat},
      {"auxiliary", &gl::PassTimes::auxiliary}, {"depth bounds", &gl::PassTimes::depthBounds},
      {"camera", &gl::PassTimes::camera}};
  double peak = 0.0;
  for (const gl::PassTimes& t : history) peak = std::max(peak, t.total());
  peak = std::max(peak * 1.1, 1e-3);
  std::vector<ImU32> colours;
  for (size_t p = 0; p < std::size(kPasses); ++p) {  // the legend, above the graph
    float r = 0.0f, g = 0.0f, b = 0.0f;
    ImGui::ColorConvertHSVtoRGB(float(p) / float(std::size(kPasses)), 0.6f, 1.0f, r, g, b);
    colours.push_back(ImGui::ColorConvertFloat4ToU32(ImVec4(r, g, b, 1.0f)));
    ImGui::TextColored(ImVec4(r, g, b, 1.0f), "%s", kPasses[p].first);
    if (p + 1 < std::size(kPasses)) ImGui::SameLine();
  }
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const ImVec2 size(ImGui::GetContentRegionAvail().x, 70.0f);
  draw->AddRectFilled(origin, ImVec2(origin.x + size.x, origin.y + size.y),
                      IM_COL32(25, 25, 30, 255));
  const auto point = [&](size_t i, double ms) {
    // One frame so far: a flat line across.
    const float t = history.size() == 1 ? float(i) : float(i) / float(history.size() - 1);
    return ImVec2(origin.x + size.x * t, origin.y + size.y * float(1.0 - ms / peak));
  };
  std::vector<double> below(history.size(), 0.0);
  for (size_t p = 0; p < std::size(kPasses); ++p) {
    std::vector<ImVec2> line;
    for (size_t i = 0; i < history.size(); ++i) {
      below[i] += history[i].*(kPasses[p].second);
      line.push_back(point(i, below[i]));
    }
    if (history.size() == 1) line.push_back(point(1, below[0]));
    draw->AddPolyline(line.data(), int(line.size()), colours[p], 0, 1.5f);
  }
  ImGui::Dummy(size);
  ImGui::Text("stacked per pass; top: frame %.1f ms (peak %.1f)", history.back().total(),
              peak / 1.1);
}

void statsSection(ViewerState& state, const FrameStats& stats) {
  if (stats.result == nullptr) return;
  const gl::RenderResult& r = *stats.result;
  ImGui::Text("%s", stats.device.c_str());
  if (!state.frameMs.empty()) {
    // The window's own frames (panel, display, renders when something changed).
    const double longest = *std::max_element(state.frameMs.begin(), state.frameMs.end());
    ImGui::Text("window frame %.1f ms (longest of the last %zu: %.1f ms)", state.frameMs.back(),
                state.frameMs.size(), longest);
  }
  // The wall clock between glFinish calls, and GPU timer queries where they time execution
  // (not llvmpipe's: the frame then has none); both are kept, the graph shows the one chosen.
  const bool gpuTimed = r.gpuTimes.has_value();
  if (gpuTimed) {
    ImGui::Checkbox("graph GPU timer queries (else wall clock)", &state.graphGpuTimes);
  } else {
    ImGui::TextWrapped("wall clock between glFinish calls; no GPU times: %s",
                       gl::kNoGpuTimesReason);
  }
  drawPassGraph(gpuTimed && state.graphGpuTimes ? state.gpuTimes : state.wallTimes);
  const gl::PassTimes g = r.gpuTimes.value_or(gl::PassTimes{});   // read only when gpuTimed
  const gl::PassTimes w = r.wallTimes.value_or(gl::PassTimes{});  // the viewer times every frame
  if (ImGui::BeginTable("passes", gpuTimed ? 3 : 2, ImGuiTableFlags_SizingFixedFit)) {
    ImGui::TableSetupColumn("pass");
    if (gpuTimed) ImGui::TableSetupColumn("GPU ms");
    ImGui::TableSetupColumn("wall ms");
    ImGui::TableHeadersRow();
    const auto row = [gpuTimed](const char* name, double gpu, double wall) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(name);
      if (gpuTimed) {
        ImGui::TableNextColumn();
        ImGui::Text("%.2f", gpu);
      }
      ImGui::TableNextColumn();
      ImGui::Text("%.2f", wall);
    };
    row("light", g.light, w.light);
    row("encode", g.encode, w.encode);
    row("blur", g.prefilter, w.prefilter);
    row("mips / SAT", g.mipsOrSat, w.mipsOrSat);
    row("auxiliary", g.auxiliary, w.auxiliary);
    row("depth bounds", g.depthBounds, w.depthBounds);
    row("camera", g.camera, w.camera);
    row("total", g.total(), w.total());
    ImGui::EndTable();
  }
  const gl::MemoryReport& m = r.memory;
  const auto mib = [](uint64_t bytes) { return double(bytes) / (1024.0 * 1024.0); };
  ImGui::TextWrapped("memory %.2f MiB: technique %.2f, SAT %.2f, light %.2f, frame %.2f",
                     mib(m.total()), mib(m.technique), mib(m.summedArea), mib(m.lightPass),
                     mib(m.frame));
  if (r.failureRatePercent > 0.0) ImGui::Text("ESM failures: %.2f %%", r.failureRatePercent);
}

void filesSection(ViewerState& state, Changes& changes) {
  char path[512];
  std::snprintf(path, sizeof path, "%s", state.settingsPath.c_str());
  if (ImGui::InputText("settings file", path, sizeof path)) state.settingsPath = path;
  changes.saveSettings = ImGui::Button("save");
  ImGui::SameLine();
  changes.loadSettings = ImGui::Button("load");
  ImGui::SameLine();
  ImGui::TextDisabled("F12: screenshot, H: hide panel");
}

}  // namespace

Changes drawSettingsPanel(ViewerState& state, const FrameStats& stats, float panelWidth) {
  Changes changes;
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x - panelWidth, 0.0f));
  ImGui::SetNextWindowSize(ImVec2(panelWidth, io.DisplaySize.y));
  ImGui::Begin("penumbra", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
  ImGui::PushItemWidth(panelWidth * 0.5f);
  if (ImGui::CollapsingHeader("scene", ImGuiTreeNodeFlags_DefaultOpen))
    sceneSection(state, changes);
  if (ImGui::CollapsingHeader("technique", ImGuiTreeNodeFlags_DefaultOpen))
    techniqueSection(state, changes);
  if (ImGui::CollapsingHeader("split view")) splitSection(state, changes);
  if (ImGui::CollapsingHeader("shadow map and filtering", ImGuiTreeNodeFlags_DefaultOpen)) {
    renderSection(state, changes);
  }
  if (ImGui::CollapsingHeader("light")) lightSection(state, changes);
  if (ImGui::CollapsingHeader("camera")) cameraSection(state, changes);
  if (ImGui::CollapsingHeader("show", ImGuiTreeNodeFlags_DefaultOpen))
    viewSection(state, stats, changes);
  if (ImGui::CollapsingHeader("time and memory", ImGuiTreeNodeFlags_DefaultOpen))
    statsSection(state, stats);
  if (ImGui::CollapsingHeader("settings file", ImGuiTreeNodeFlags_DefaultOpen))
    filesSection(state, changes);
  if (!state.message.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, state.messageIsError ? ImVec4(1.0f, 0.45f, 0.4f, 1.0f)
                                                              : ImVec4(0.6f, 0.9f, 0.6f, 1.0f));
    ImGui::TextWrapped("%s", state.message.c_str());
    ImGui::PopStyleColor();
  }
  ImGui::PopItemWidth();
  ImGui::End();
  return changes;
}

}  // namespace penumbra::viewer
