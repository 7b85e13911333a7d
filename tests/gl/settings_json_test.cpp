// Settings files: what settingsJson writes, applySettingsJson reads back to the same settings,
// and the command line's explicit options are kept.
#include <gtest/gtest.h>

#include "penumbra/error.h"
#include "penumbra/gl/settings_json.h"
#include "penumbra/params.h"

namespace penumbra::gl {
namespace {

Settings everyKeyAwayFromItsDefault() {
  Settings s;
  s.scene = "street";
  s.techniques = {Technique::Lvsm, Technique::Esm, Technique::PowerCdf};
  RenderSettings& r = s.render;
  setParam(Technique::Lvsm, r.params, "minVariance", "0.002");
  // Non-uniform splits (a file also carries the layer count they imply), and a placement other
  // than the fixed one that setting splits selects.
  setParam(Technique::Lvsm, r.params, "splits", "0.125,0.25,0.75");
  setParam(Technique::Lvsm, r.params, "placement", "lloyd");
  setParam(Technique::PowerCdf, r.params, "splits", "0.0625,0.5");
  setParam(Technique::Esm, r.params, "classifier", "zmax");
  r.shadowMapSize = 512;
  r.msaaSamples = 4;
  r.blur = {BlurKernel::Box, 3, 1.25f};
  r.filter = FilterMode::Anisotropic;
  r.anisotropy = 8;
  r.width = 321;
  r.height = 123;
  r.normalOffsetTexels = 1.5f;
  r.cascades.count = 3;
  r.cascades.lambda = 0.25f;
  r.cascades.distances = {5.0f, 20.0f};
  r.cascades.fit = CascadeFit::Tight;
  r.cascades.fitDepthBounds = true;
  r.cascades.blendBand = 0.2f;
  r.cascades.maxDistance = 60.0f;
  r.overlay = Overlay::Cascades;
  s.view.lightDirection = glm::vec3(0.1f, -1.0f, 0.3f);
  s.view.cameraPosition = glm::vec3(1.0f, 2.0f, 3.0f);
  s.view.cameraTarget = glm::vec3(0.0f, 0.5f, 0.0f);
  s.view.cameraFovDegrees = 50.0f;
  return s;
}

TEST(SettingsJson, ReadsBackEverySettingItWrites) {
  const Settings written = everyKeyAwayFromItsDefault();
  Settings read;
  applySettingsJson(settingsJson(written), "test", read);
  EXPECT_EQ(read.scene, written.scene);
  EXPECT_EQ(read.techniques, written.techniques);
  const RenderSettings& a = read.render;
  const RenderSettings& b = written.render;
  for (Technique t : written.techniques) {
    for (const ParamSpec& spec : techniqueParamSpecs(t)) {
      EXPECT_EQ(formatParam(t, a.params, spec.name), formatParam(t, b.params, spec.name))
          << techniqueId(t) << "." << spec.name;
    }
  }
  EXPECT_EQ(a.shadowMapSize, b.shadowMapSize);
  EXPECT_EQ(a.msaaSamples, b.msaaSamples);
  EXPECT_EQ(a.blur.kernel, b.blur.kernel);
  EXPECT_EQ(a.blur.radius, b.blur.radius);
  EXPECT_EQ(a.blur.sigma, b.blur.sigma);
  EXPECT_EQ(a.filter, b.filter);
  EXPECT_EQ(a.anisotropy, b.anisotropy);
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_EQ(a.normalOffsetTexels, b.normalOffsetTexels);
  EXPECT_EQ(a.cascades.count, b.cascades.count);
  EXPECT_EQ(a.cascades.lambda, b.cascades.lambda);
  EXPECT_EQ(a.cascades.distances, b.cascades.distances);
  EXPECT_EQ(a.cascades.fit, b.cascades.fit);
  EXPECT_EQ(a.cascades.fitDepthBounds, b.cascades.fitDepthBounds);
  EXPECT_EQ(a.cascades.blendBand, b.cascades.blendBand);
  EXPECT_EQ(a.cascades.maxDistance, b.cascades.maxDistance);
  EXPECT_EQ(a.overlay, b.overlay);
  EXPECT_EQ(read.view.lightDirection, written.view.lightDirection);
  EXPECT_FALSE(read.view.lightPosition.has_value());
  EXPECT_EQ(read.view.cameraPosition, written.view.cameraPosition);
  EXPECT_EQ(read.view.cameraTarget, written.view.cameraTarget);
  EXPECT_EQ(read.view.cameraFovDegrees, written.view.cameraFovDegrees);
}

TEST(SettingsJson, ReadsBackASingleLayer) {
  Settings written;
  written.techniques = {Technique::PowerCdf};
  setParam(Technique::PowerCdf, written.render.params, "layers", "1");
  Settings read;
  applySettingsJson(settingsJson(written), "test", read);
  EXPECT_EQ(formatParam(Technique::PowerCdf, read.render.params, "layers"), "1");
}

TEST(SettingsJson, RefusesALayerCountItsSplitsDisagreeWith) {
  Settings s;
  try {
    applySettingsJson(R"({"param": {"lvsm": {"layers": 3, "splits": "0.1,0.2,0.3"}}})", "f.json",
                      s);
    FAIL() << "accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("\"param.lvsm.splits\" places 4 layers, but \"layers\" is 3"),
              std::string::npos)
        << e.what();
  }
}

TEST(SettingsJson, RefusesCameraAndLightVectorsBeyondTheWorldRange) {
  for (const char* json : {R"({"light": {"direction": [1e30, 1e30, 1e30]}})",
                           R"({"camera": {"position": [2e6, 0, 0]}})"}) {
    Settings s;
    EXPECT_THROW(applySettingsJson(json, "f.json", s), Error) << json;
  }
  Settings s;  // the bound itself is a position like any other
  applySettingsJson(R"({"camera": {"position": [1e6, 0, 0]}})", "f.json", s);
  EXPECT_EQ(s.view.cameraPosition, glm::vec3(1e6f, 0.0f, 0.0f));
}

TEST(SettingsJson, KeepsTheKeysTheCommandLineGave) {
  Settings s;
  s.render.shadowMapSize = 64;
  const std::string given[] = {"shadow-size"};
  applySettingsJson(R"({"shadow-size": 2048, "width": 100})", "test", s, given);
  EXPECT_EQ(s.render.shadowMapSize, 64);
  EXPECT_EQ(s.render.width, 100);
}

TEST(SettingsJson, RefusesUnknownKeysEvenWhenSkipped) {
  Settings s;
  const std::string given[] = {"shadowsize"};
  EXPECT_THROW(applySettingsJson(R"({"shadowsize": 2048})", "test", s, given), Error);
}

TEST(SettingsJson, ALightPositionMakesASpotLightAndReplacesTheDirection) {
  Settings s;
  s.view.lightDirection = glm::vec3(0.0f, -1.0f, 0.0f);
  applySettingsJson(R"({"light": {"position": [0, 5, 0], "spot_angle": 40}})", "test", s);
  EXPECT_FALSE(s.view.lightDirection.has_value());
  EXPECT_EQ(s.view.lightPosition, glm::vec3(0.0f, 5.0f, 0.0f));
  EXPECT_EQ(s.view.spotAngleDegrees, 40.0f);
}

TEST(SettingsJson, ReadsBackTheSplitViewsRightSide) {
  Settings written;
  written.split = SplitSettings{};
  written.split->technique = Technique::Msm;
  setParam(Technique::Msm, written.split->params, "momentBias", "0.0005");
  written.split->divider = 0.25f;
  Settings read;
  applySettingsJson(settingsJson(written), "test", read);
  ASSERT_TRUE(read.split.has_value());
  EXPECT_EQ(read.split->technique, Technique::Msm);
  EXPECT_EQ(read.split->divider, 0.25f);
  for (const ParamSpec& spec : techniqueParamSpecs(Technique::Msm)) {
    EXPECT_EQ(formatParam(Technique::Msm, read.split->params, spec.name),
              formatParam(Technique::Msm, written.split->params, spec.name))
        << spec.name;
  }
  // The left side's parameters are not the right side's.
  EXPECT_NE(formatParam(Technique::Msm, read.render.params, "momentBias"),
            formatParam(Technique::Msm, read.split->params, "momentBias"));
  // Without a split, none is written or read.
  Settings plain;
  applySettingsJson(settingsJson(Settings{}), "test", plain);
  EXPECT_FALSE(plain.split.has_value());
}

TEST(SettingsJson, RefusesABadSplitSideWithItsKey) {
  const auto message = [](const char* json) {
    Settings s;
    try {
      applySettingsJson(json, "f.json", s);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message(R"({"split": {"technique": "nope"}})").find("\"split.technique\""),
            std::string::npos);
  EXPECT_NE(message(R"({"split": {"divider": 2}})").find("\"split.divider\""), std::string::npos);
  EXPECT_NE(
      message(R"({"split": {"param": {"vsm": {"nope": 1}}}})").find("\"split.param.vsm.nope\""),
      std::string::npos);
  EXPECT_NE(message(R"({"split": {"side": "right"}})").find("split takes"), std::string::npos);
  EXPECT_NE(message(R"({"split": 3})").find("must be an object"), std::string::npos);
}

}  // namespace
}  // namespace penumbra::gl
