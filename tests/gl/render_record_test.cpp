// The render record says what the frame measured: times that were not taken are null, not 0.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "penumbra/gl/render_record.h"
#include "penumbra/gl/renderer.h"
#include "penumbra/params.h"
#include "penumbra/scene.h"

namespace penumbra::gl {
namespace {

nlohmann::json recordOf(const RenderResult& result) {
  RenderSettings settings;
  settings.technique = Technique::Vsm;
  return nlohmann::json::parse(
      renderRecordJson(makeBuiltinScene("planar"), settings, result, "test device", {}));
}

TEST(RenderRecord, TimesNotTakenAreNullAndTakenOnesAreWrittenAsMeasured) {
  RenderResult untimed;
  untimed.params = defaultTechniqueParams();
  untimed.visibility = Image(2, 2, 1);
  const nlohmann::json none = recordOf(untimed);
  EXPECT_TRUE(none.at("wall_ms").is_null()) << "an untimed frame's wall times read as measured";
  EXPECT_TRUE(none.at("gpu_ms").is_null());

  RenderResult timed = untimed;
  PassTimes wall;
  wall.light = 1.5;
  wall.camera = 2.25;
  timed.wallTimes = wall;
  const nlohmann::json some = recordOf(timed);
  // Exact: the values are dyadic and JSON carries doubles through.
  EXPECT_EQ(some.at("wall_ms").at("light").get<double>(), 1.5);
  EXPECT_EQ(some.at("wall_ms").at("camera").get<double>(), 2.25);
  EXPECT_EQ(some.at("wall_ms").at("total").get<double>(), 3.75);
  EXPECT_TRUE(some.at("gpu_ms").is_null());
}

}  // namespace
}  // namespace penumbra::gl
